// tripath's Python module: load a scene, render it, save and measure images (compare and benchmark
// are in evaluation.cpp). `render` fills the library's
// render request (requests/render_request.h) from its keyword arguments, so the same settings
// give the same bits as `tripath render`, and bad values are refused with the same reasons (as
// ValueError, in Python's spelling of the parameters). The image comes back as a NumPy array that
// owns the image's pixels, without a copy. The GIL is released while rendering; between passes the
// render takes it back to run the progress callback and Python's signal handlers, so Ctrl-C stops
// the render at the next pass and the partial image is returned.
#include "module.h"

#include <pybind11/functional.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "requests/integrator_parameters.h"
#include "requests/memory_check.h"
#include "image/exposure.h"
#include "evaluation/flip.h"
#include "evaluation/metrics.h"
#include "scenes/builtin_scenes.h"

namespace tripath::python {

py::array_t<float> toArray(Image image) {
    auto* owned = new Image(std::move(image));
    py::capsule free(owned, [](void* p) { delete static_cast<Image*>(p); });
    const auto h = py::ssize_t(owned->height), w = py::ssize_t(owned->width);
    return py::array_t<float>({h, w, py::ssize_t(3)}, owned->rgb.data(), free);
}

Image fromArray(const ArrayIn& a, const char* what) {
    if (a.ndim() != 3 || a.shape(2) != 3)
        throw InputError(std::string(what) + " must be an array of shape (height, width, 3)");
    Image img(int(a.shape(1)), int(a.shape(0)));
    std::copy(a.data(), a.data() + img.rgb.size(), img.rgb.begin());
    return img;
}

std::unique_ptr<PyScene> loadPyScene(const std::string& nameOrPath, bool allowExternalFiles,
                                     const std::optional<std::string>& environment, std::optional<float> environmentScale) {
    Warnings warnings;
    RenderRequest where;
    where.scene = nameOrPath;
    where.gltf.allowExternalFiles = allowExternalFiles;
    if (environment) where.environment = *environment, where.environmentGiven = true;
    if (environmentScale) where.environmentScale = *environmentScale, where.environmentScaleGiven = true;
    validateValues(where, Spelling::Python);
    auto scene = std::make_unique<PyScene>(where, warnings);
    warnings.raise();
    return scene;
}

void setMemoryLimit(RenderRequest& r, const py::object& limit) {
    if (limit.is_none()) return;
    if (!py::isinstance<py::int_>(limit) && !py::isinstance<py::str>(limit))
        throw py::type_error("memory_limit must be a number of bytes or a size such as '8G', not " +
                             std::string(py::str(py::type::of(limit).attr("__name__"))));
    r.memoryLimit = parseMemoryLimit(std::string(py::str(limit)), Spelling::Python);
    r.memoryLimitGiven = true;
}

SceneArgument::SceneArgument(const py::object& scene) {
    if (py::isinstance<PyScene>(scene)) {
        scene_ = &scene.cast<PyScene&>();
        return;
    }
    if (!py::isinstance<py::str>(scene) && !py::hasattr(scene, "__fspath__"))
        throw py::type_error("scene must be a tripath.Scene (from load()), a built-in scene's name or a glTF file's "
                             "path, not " + std::string(py::str(py::type::of(scene).attr("__name__"))));
    const py::object name = py::module_::import("os").attr("fspath")(scene);
    if (!py::isinstance<py::str>(name)) throw py::type_error("scene: a path must be a str, not bytes");
    loaded_ = loadPyScene(name.cast<std::string>(), false);
    scene_ = loaded_.get();
}

namespace {

std::string keywordOf(const IntegratorParameter& p) {
    std::string k = p.flag;
    std::replace(k.begin(), k.end(), '-', '_');
    return k;
}

std::vector<std::string> keywordOptions() {
    std::vector<std::string> names;
    for (const IntegratorParameter& p : integratorParameters())
        if (p.keyword) names.push_back(keywordOf(p));
    return names;
}

// "Keyword options: rr_depth (pt, lt, ...: help), ...": the docstring's part made from the table.
std::string keywordOptionsDoc() {
    std::vector<std::string> items;
    const RenderRequest defaults;
    for (const IntegratorParameter& p : integratorParameters()) {
        if (!p.keyword) continue;
        const std::string shown = p.shownDefault(defaults);
        items.push_back(fmt::format("{} ({}{})", keywordOf(p), describe(p), shown.empty() ? "" : "; default " + shown));
    }
    return fmt::format("Keyword options: {}.", fmt::join(items, "; "));
}

// The integrator options taken as keywords beyond the named parameters (integrator_parameters.h).
void applyIntegratorOptions(RenderRequest& r, const py::kwargs& options) {
    for (const auto& [key, value] : options) {
        const std::string k = py::str(key);
        if (k == "rr_depth") r.rrDepth = value.cast<int>();
        else if (k == "radius") r.merge.radius = value.cast<float>(), r.radiusGiven = true;
        else if (k == "radius_factor") r.merge.radiusFactor = value.cast<float>(), r.radiusFactorGiven = true;
        else if (k == "radius_pixels") r.merge.radiusPixels = value.cast<float>(), r.radiusPixelsGiven = true;
        else if (k == "alpha") r.merge.alpha = value.cast<float>(), r.alphaGiven = true;
        else if (k == "light_paths") r.lightPaths = value.cast<int64_t>(), r.lightPathsGiven = true;
        else if (k == "sampler") r.sampler = py::str(value).cast<std::string>(), r.samplerGiven = true;  // a non-text value is refused by name
        else if (k == "bootstrap") r.metropolis.bootstrap = value.cast<int64_t>(), r.bootstrapGiven = true;
        else if (k == "chains") r.metropolis.chains = value.cast<int>(), r.chainsGiven = true;
        else if (k == "large_step") r.metropolis.largeStep = value.cast<float>(), r.largeStepGiven = true;
        else
            throw InputError(fmt::format("unknown option '{}' (the integrator options are {})", k.substr(0, 40),
                                         fmt::join(keywordOptions(), ", ")));
    }
}

}  // namespace

RenderRequest requestOf(const RenderRequest& where, const std::string& integrator, int width,
                        int height, uint64_t seed, int maxDepth, const std::string& mis, int threads,
                        const py::kwargs& options) {
    RenderRequest request;
    request.scene = where.scene;
    request.gltf = where.gltf;
    request.environment = where.environment;
    request.environmentGiven = where.environmentGiven;
    request.environmentScale = where.environmentScale;
    request.environmentScaleGiven = where.environmentScaleGiven;
    request.integrator = integrator;
    request.width = width;
    request.height = height;
    request.seed = seed;
    request.maxDepth = maxDepth;
    request.mis = mis;
    request.threads = threads;
    applyIntegratorOptions(request, options);
    return request;
}

namespace {

py::dict strategyLayers(const RenderResult& r) {
    py::dict layers;
    for (const Strategy& st : r.film.strategies()) {
        py::dict both;
        both["weighted"] = toArray(r.film.strategyImage(st, true, r.passes));
        both["unweighted"] = toArray(r.film.strategyImage(st, false, r.passes));
        layers[py::make_tuple(st.s, st.t, st.merge ? "merge" : "connect")] = both;
    }
    return layers;
}

py::dict renderScene(const py::object& sceneArgument, const std::string& integrator, std::optional<int> spp,
                     std::optional<double> seconds, int width, int height, uint64_t seed, int maxDepth,
                     const std::string& mis, int threads,
                     bool depthImages, int strategyImages, const std::function<void(int, double)>& progress,
                     const py::object& memoryLimit, const py::kwargs& options) {
    const SceneArgument argument(sceneArgument);
    PyScene& scene = *argument;
    RenderRequest request =
        requestOf(scene.where(), integrator, width, height, seed, maxDepth, mis, threads, options);
    if (spp) request.spp = *spp, request.sppGiven = true;
    if (seconds) request.seconds = *seconds, request.timeGiven = true;
    request.depthImages = depthImages;
    request.strategyImages = strategyImages;
    setMemoryLimit(request, memoryLimit);
    if (request.sppGiven && request.timeGiven) throw InputError("spp and seconds exclude each other: give one");
    validate(request, Spelling::Python);

    const std::shared_ptr<const Scene> shared = scene.at(width, height);
    const Scene& built = *shared;
    const auto method = makeIntegrator(request.integrator, integratorSettings(request));
    RenderSettings settings = renderSettings(request, Spelling::Python);
    Watch watch;
    settings.stop = &watch.stop;
    settings.progress = [&](int passes, double elapsed) {
        watch.between([&] {
            if (progress) progress(passes, elapsed);
        });
    };
    std::optional<RenderResult> result;
    {
        const py::gil_scoped_release released;
        result.emplace(tripath::render(built, *method, settings));
    }
    watch.raiseFailure();
    py::dict out;
    out["image"] = toArray(result->image());
    if (depthImages) {
        py::list depth;
        for (int k = 1; k <= settings.layers.depthImages; ++k) depth.append(toArray(result->film.depthImage(k, result->passes)));
        out["depth"] = depth;
    }
    if (strategyImages > 0) out["strategies"] = strategyLayers(*result);
    out["spp"] = result->passes;
    out["seconds"] = result->seconds;
    out["interrupted"] = watch.interrupted;
    out["dropped_samples"] = result->droppedSamples;
    out["guarded_weights"] = result->guardedWeights;
    out["counters"] = counters(result->stats.events);
    py::dict metadata;
    for (const auto& [key, value] : renderMetadata(request, built, *method, *result)) metadata[py::str(key)] = value;
    out["metadata"] = metadata;
    return out;
}

// Metadata from a dict of str keys; each value is written as str(value).
Metadata metadataOf(const std::optional<py::dict>& dict) {
    Metadata meta;
    if (!dict) return meta;
    for (const auto& [key, value] : *dict) {
        if (!py::isinstance<py::str>(key))
            throw py::type_error("metadata keys must be str, not " +
                                 std::string(py::str(py::type::of(key).attr("__name__"))));
        meta.emplace_back(key.cast<std::string>(), std::string(py::str(value)));
    }
    return meta;
}

void writeExrFile(const std::filesystem::path& path, const ArrayIn& image, const std::optional<py::dict>& metadata) {
    const Metadata meta = metadataOf(metadata);
    writeExr(path.string(), fromArray(image, "image"), meta);
}

float writePngFile(const std::filesystem::path& path, const ArrayIn& image, std::optional<float> exposure) {
    if (exposure && !std::isfinite(*exposure)) throw InputError("exposure must be a finite number of stops");
    return writePreviewPng(path.string(), fromArray(image, "image"), exposure);
}

py::tuple readExrFile(const std::filesystem::path& path) {
    Metadata meta;
    Image img = readExr(path.string(), &meta);
    py::dict d;
    for (const auto& [key, value] : meta) d[py::str(key)] = value;
    return py::make_tuple(toArray(std::move(img)), d);
}

ErrorMetrics errors(const py::array_t<float, py::array::c_style | py::array::forcecast>& image,
                    const py::array_t<float, py::array::c_style | py::array::forcecast>& reference, double epsilon) {
    return compareImages(fromArray(image, "image"), fromArray(reference, "reference"), epsilon);
}

}  // namespace

}  // namespace tripath::python

PYBIND11_MODULE(tripath, m) {
    using namespace tripath;
    using namespace tripath::python;
    using Array = py::array_t<float, py::array::c_style | py::array::forcecast>;
    m.doc() = "tripath: light transport in the three-point form (path tracing, light tracing, BDPT, VCM, BPM, PPM)";
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const InputError& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        }
    });

    py::class_<PyScene>(m, "Scene", "A loaded scene: load() makes one; render() renders it at any size")
        .def_property_readonly("name", &PyScene::name)
        .def_property_readonly("triangles", &PyScene::triangles)
        .def("__repr__", [](const PyScene& s) { return "<tripath.Scene '" + s.name() + "'>"; });

    m.def("load", &loadPyScene, py::arg("path_or_builtin"), py::arg("allow_external_files") = false,
        py::arg("environment") = py::none(), py::arg("environment_scale") = py::none(),
        "Loads a built-in scene by name (see scenes()) or a .gltf/.glb file. ValueError for an unknown name or a bad "
        "file, with the command line's one-line message; what the loader ignored or dropped comes as UserWarning. "
        "allow_external_files lets a glTF file's buffers name files outside its folder. environment lights the scene "
        "from infinitely far away, as `tripath render --environment`: an equirectangular map's path (.exr, .hdr, ...; "
        "linear radiance) or 'R,G,B' for a constant; a direction d = (x, y, z) toward the sky (glTF world space, +Y "
        "up) reads column u = 0.5 + atan2(x, -z) / (2 pi) and row v = acos(y) / pi (row 0 at the top); "
        "environment_scale multiplies it. Renders of the scene record both in their metadata.");

    m.def("scenes", [] {
        py::dict d;
        for (const BuiltinInfo& b : builtinScenes()) d[py::str(b.name)] = b.description;
        return d;
    }, "The built-in scenes: name -> what each one is for");

    static const std::string renderDoc =
        "Renders scene (a Scene from load(), or a built-in name or glTF path, loaded as load() does) with one "
        "integrator (pt, lt, bdpt, vcm, bpm, ppm, mlt) for spp passes or seconds of wall-clock time (16 passes when "
        "neither is given). Returns a dict: image (float32 array, height x width x 3, linear radiance, no copy), depth "
        "(with depth_images: one image per path length k = 1..max_depth), strategies (with strategy_images = K: "
        "{(s, t, 'connect' | 'merge'): {'weighted', 'unweighted'}} for k <= K; " +
        describe(integratorParameter("strategy-images")) +
        "), spp, seconds, interrupted, dropped_samples, guarded_weights, counters (rays, BSDF calls, ...), metadata "
        "(as the EXR's, tripath:memory-estimate among them). progress(passes, seconds) is called after each pass. The "
        "same settings give the same image as `tripath render`, whatever the thread count. Ctrl-C stops at the next "
        "pass and returns what is done (interrupted = True). A render whose memory estimate (film, light paths, "
        "scene) exceeds memory_limit (bytes, or a size such as '8G'; default: what the machine can give the process) "
        "raises ValueError before it starts, as `tripath render --memory-limit` refuses it. " +
        keywordOptionsDoc();
    m.def("render", &renderScene, py::arg("scene"), py::arg("integrator") = "bdpt", py::arg("spp") = py::none(),
          py::arg("seconds") = py::none(), py::arg("width") = 512, py::arg("height") = 512, py::arg("seed") = 1,
          py::arg("max_depth") = 16, py::arg("mis") = "power", py::arg("threads") = 0, py::arg("depth_images") = false,
          py::arg("strategy_images") = 0, py::arg("progress") = py::none(), py::arg("memory_limit") = py::none(),
          renderDoc.c_str());

    m.def("read_exr", &readExrFile, py::arg("path"),
          "Reads an EXR as (float32 array height x width x 3, {'tripath:...': value} metadata)");
    m.def("write_exr", &writeExrFile, py::arg("path"), py::arg("image"), py::arg("metadata") = py::none(),
          "Writes image (an array height x width x 3, linear radiance) as a 32-bit float EXR, as `tripath render` "
          "writes its --out: atomically, each metadata item a string attribute (str(value)); render()'s "
          "'metadata' are the command line's, and read_exr() reads back those named 'tripath:...'");
    m.def("write_png", &writePngFile, py::arg("path"), py::arg("image"), py::arg("exposure") = py::none(),
          "Writes an 8-bit sRGB PNG preview of image, as `tripath render --png`: scaled by 2^exposure stops, or, "
          "with exposure None, exposed from the image (the 98th percentile of the luminance of its pixels above 0 "
          "maps to white, in whole thirds of a stop). Returns the exposure used, in stops");

    defineEvaluation(m);

    py::module_ metrics = m.def_submodule("metrics", "Error metrics of an image against a reference (arrays h x w x 3)");
    metrics.def("relmse", [](const Array& a, const Array& r, double eps) { return errors(a, r, eps).relMse; },
                py::arg("image"), py::arg("reference"), py::arg("epsilon") = 0.01,
                "Mean over pixels and channels of (x - r)^2 / (r^2 + epsilon)");
    metrics.def("mse", [](const Array& a, const Array& r) { return errors(a, r, 0.01).mse; }, py::arg("image"),
                py::arg("reference"), "Mean over pixels and channels of (x - r)^2");
    metrics.def("mae", [](const Array& a, const Array& r) { return errors(a, r, 0.01).mae; }, py::arg("image"),
                py::arg("reference"), "Mean over pixels and channels of |x - r|");
    metrics.def("tail_share", [](const Array& a, const Array& r) { return errors(a, r, 0.01).tailShare; },
                py::arg("image"), py::arg("reference"),
                "Share of the relMSE sum carried by the worst 0.1 % of pixels (at least one)");
    metrics.def(
        "relmse_without_tail",
        [](const Array& a, const Array& r) { return relMseWithoutTail(errors(a, r, 0.01), size_t(a.shape(0) * a.shape(1))); },
        py::arg("image"), py::arg("reference"), "relMSE with the worst 0.1 % of pixels left out");
    metrics.def(
        "hdr_flip",
        [](const Array& a, const Array& r) {
            const Image reference = fromArray(r, "reference");
            return hdrFlip(fromArray(a, "image"), reference, flipExposures(reference));
        },
        py::arg("image"), py::arg("reference"),
        "Mean HDR-FLIP (Andersson et al. 2021) at exposures set from the reference, 67 pixels per degree");
}
