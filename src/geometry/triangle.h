// A triangle of the scene as the renderer keeps it: its corners, per-corner shading normals, the
// geometric normal and the index of its material. A header of its own so that what needs the
// triangles alone (the emitters, which sample points on them) does not see the Scene and Embree.
#pragma once
#include "core/vec.h"

namespace tripath {

struct Triangle {
    Vec3 p[3];
    Vec3 n[3];            // shading normals per corner (the geometric normal when the mesh has none)
    Vec3 ng;              // unit geometric normal by winding, computed once at load
    bool smooth = false;  // true when n[] came from the file
    int material = 0;
    Vec3 geometricNormal() const { return ng; }
    float area() const { return 0.5f * length(cross(p[1] - p[0], p[2] - p[0])); }
};

}  // namespace tripath
