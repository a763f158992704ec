// What the Python module's files share: the loaded scene, warnings raised in Python, the watch
// that keeps Ctrl-C and callbacks working while the library runs without the GIL, and the
// conversions between the library's values and Python's.
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/stats.h"
#include "core/warnings.h"
#include "geometry/scene.h"
#include "image/image.h"
#include "requests/render_request.h"
#include "scenes/scene_source.h"

namespace tripath::python {

namespace py = pybind11;

// Warnings gathered while the library works (without the GIL, perhaps), then raised in Python as
// UserWarning once it is back.
struct Warnings {
    std::vector<std::string> messages;
    WarningSink sink() {
        return [this](const std::string& m) { messages.push_back(oneLine(m)); };  // one line, as on the command line
    }
    void raise() const {
        for (const std::string& m : messages)
            if (PyErr_WarnEx(PyExc_UserWarning, m.c_str(), 2) != 0) throw py::error_already_set();
    }
};

// A loaded scene: built once, at the default size (so a scene that cannot be rendered is refused
// by load()), and reframed for a render at another size, sharing its BVH (Scene's reframing
// constructor); the last size asked for is kept. A render holds its own reference to the scene it
// renders: another thread may ask for another size meanwhile (the GIL is released).
class PyScene {
public:
    // `where`: the request's scene, glTF options and environment (the rest is unread).
    PyScene(const RenderRequest& where, Warnings& warnings) : where_(where), base_(loadScene(where_, warnings.sink())), framed_(base_) {}
    const std::string& name() const { return where_.scene; }
    // A request for this scene: its name, glTF options and environment set, the rest defaults.
    const RenderRequest& where() const { return where_; }
    std::shared_ptr<const Scene> at(int width, int height) {
        if (framed_->camera().width() != width || framed_->camera().height() != height)
            framed_ = std::make_shared<const Scene>(*base_, width, height);
        return framed_;
    }
    size_t triangles() const { return base_->triangles().size(); }

private:
    RenderRequest where_;
    std::shared_ptr<const Scene> base_, framed_;
};

// load(): the built-in scene or glTF file `nameOrPath` names, under the environment `environment`
// names (requests/environment_spec.h; none if empty), what the loader ignored or dropped raised as
// UserWarning.
std::unique_ptr<PyScene> loadPyScene(const std::string& nameOrPath, bool allowExternalFiles,
                                     const std::optional<std::string>& environment = std::nullopt,
                                     std::optional<float> environmentScale = std::nullopt);

// The scene argument of render() and compare(): a Scene from load(), or a built-in scene's name or
// a glTF file's path (str or os.PathLike), loaded here as load() loads it. Any other type is a
// TypeError of one line (pybind's own would list the whole signature).
class SceneArgument {
public:
    explicit SceneArgument(const py::object& scene);
    PyScene& operator*() const { return *scene_; }

private:
    std::unique_ptr<PyScene> loaded_;
    PyScene* scene_ = nullptr;
};

// Long work runs without the GIL; between passes it takes the GIL back to run Python's signal
// handlers and the caller's callback. Ctrl-C (KeyboardInterrupt, from the handler or inside the
// callback) sets `interrupted` and stops the work at that pass; any other exception from the
// callback stops it too and is raised once the work has returned.
class Watch {
public:
    std::atomic<bool> stop{false};
    bool interrupted = false;

    template <class Callback>
    void between(Callback&& callback) {
        const py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) {
            PyErr_Clear();
            return interrupt();
        }
        try {
            callback();
        } catch (py::error_already_set& e) {
            if (e.matches(PyExc_KeyboardInterrupt)) return interrupt();
            failure_.emplace(std::move(e));
            stop = true;
        }
    }
    void raiseFailure() {
        if (failure_) throw std::move(*failure_);
    }

private:
    void interrupt() {
        interrupted = true;
        stop = true;
    }
    std::optional<py::error_already_set> failure_;
};

// The memory_limit keyword of render(), compare() and benchmark(): None (what the machine has), a
// number of bytes or a size such as "8G" (requests/memory_check.h), into `r`; ValueError for
// another value, TypeError for another type.
void setMemoryLimit(RenderRequest& r, const py::object& limit);

// An H×W×3 float32 array that owns `image`'s pixels (moved, not copied).
py::array_t<float> toArray(Image image);
using ArrayIn = py::array_t<float, py::array::c_style | py::array::forcecast>;
// An H×W×3 array (any float type) as an Image; ValueError naming `what` for another shape.
Image fromArray(const ArrayIn& a, const char* what);
// The request every function fills from its keywords: the scene (`where`: its name, glTF options and
// environment), the common settings and the integrator options (rr_depth, radius, radius_factor,
// radius_pixels, alpha).
RenderRequest requestOf(const RenderRequest& where, const std::string& integrator, int width,
                        int height, uint64_t seed, int maxDepth, const std::string& mis, int threads,
                        const py::kwargs& options);
// Every event counter of core/stats.h by its key: a render's counts, or (benchmark) means over runs.
template <class T>
py::dict counters(const std::array<T, kEventCount>& events) {
    py::dict d;
    for (int e = 0; e < kEventCount; ++e) d[py::str(eventKey(Event(e)))] = events[size_t(e)];
    return d;
}

// evaluation.cpp: compare() and benchmark() on the module.
void defineEvaluation(py::module_& m);

}  // namespace tripath::python
