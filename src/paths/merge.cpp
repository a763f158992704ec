#include "paths/merge.h"

#include "paths/kernels.h"

namespace tripath {

Connection merge(const Scene& scene, std::span<const Vertex> light, int s, const SubpathView& camera, int t,
                 const MisContext& mis) {
    Connection c;
    const Vertex& y = light[s - 1];
    const Vertex& yBefore = light[s - 2];
    const Vertex& z = camera[t - 1];
    const Vertex& zBefore = camera[t - 2];
    if (z.delta || y.delta || !(dot(y.ng, z.ng) > 0)) return c;
    const Segment incoming(y, yBefore), toCamera(z, zBefore);
    const LocalScattering at(scene, z, camera.bsdf(t - 1), incoming.towardB(), toCamera.towardB());
    c.unweighted = z.beta * rho(at.value(), traced(z, zBefore)) * y.beta * (1.0f / mis.constants.mergeEta);
    if (isBlack(c.unweighted)) return c;
    // The reference connection (s−1, t) joins y_{s−2} to z_{t−1}: z_{t−1}'s light-side pdf is the
    // light walk's step to y_{s−1}; y_{s−3}'s pdf through y_{s−2} from the merged vertex is the
    // one the light walk recorded when it went on from y_{s−2} to y_{s−1}.
    Junction junction;
    junction.cameraEnd = y.pdfFwd;
    junction.cameraBeforeEnd = toCamera.toArea(at.pdfTowardCamera(), zBefore);
    junction.lightEnd = incoming.toArea(at.pdfTowardLight(mis.constants.lightPaths), yBefore);
    if (s >= 3) junction.lightBeforeEnd = light[s - 3].pdfRev;
    if (mis.measure.on)
        c.techniques = mergeTechniqueSums(light, s, camera.vertices, t, junction, mis.measured());
    else
        c.setWeight(mergeWeight(light, s, camera.vertices, t, junction, mis));
    return c;
}

}  // namespace tripath
