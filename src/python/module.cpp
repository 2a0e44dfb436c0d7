// The compiled part of the Python package `erpt` (python/erpt/__init__.py re-exports it):
// scenes, renders, images and errors over the same integrator registry and option tables as
// the CLI. A render's settings come from erpt/render_request.h as the CLI's do, so the image
// is bit-identical to the CLI's for the same scene, seed and options.
//
// A render runs on a thread of its own while the calling thread waits with the GIL released
// (other Python threads run); every 50 ms the caller takes the GIL back to deliver progress
// and to check for signals: Ctrl-C (KeyboardInterrupt) stops the render between its passes and
// returns the passes done, as the CLI does.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <stdexcept>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <thread>

#include "erpt/error.h"
#include "erpt/erpt_settings.h"
#include "erpt/image_io.h"
#include "erpt/image_metrics.h"
#include "erpt/pssmlt_settings.h"
#include "erpt/integrators.h"
#include "erpt/render.h"
#include "erpt/render_request.h"
#include "erpt/scene_loader.h"
#include "erpt/scene_names.h"

namespace py = pybind11;

namespace erpt {
namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// erpt.Error: every InputError and UsageError, with the same one-line text as the CLI's.
// erpt.OptionTypeError and erpt.OptionValueError (subclasses of it and of TypeError and
// ValueError): a render option of the wrong type, or out of the range the CLI accepts.
PyObject* errorType = nullptr;
PyObject* optionTypeErrorType = nullptr;
PyObject* optionValueErrorType = nullptr;
// erpt.SceneWarning: the scene loader's warnings, as Python warnings.
PyObject* sceneWarningType = nullptr;

struct OptionTypeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct OptionValueError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// os.fspath: a str or a path-like object (pathlib.Path) as a path string.
std::string pathOf(const py::object& path) {
  return py::module_::import("os").attr("fspath")(path).cast<std::string>();
}

// The Embree scene of a loaded scene, built by its first render and shared by the next ones
// (and by renders from several Python threads at once: the mutex guards the first build).
struct SceneTracer {
  std::mutex mutex;
  std::shared_ptr<const Tracer> tracer;
};

struct PyScene {
  std::shared_ptr<const Scene> scene;
  std::string path;
  std::shared_ptr<SceneTracer> tracer = std::make_shared<SceneTracer>();
};

struct PyResult {
  RgbImage image;
  py::dict stats;
  py::list curve;  // with a reference: {seconds, mse, rel_mse} after every pass
  std::vector<std::pair<std::string, RgbImage>> images;  // RenderStats::extraImages
};

// An image the render made on the way (after a group of sample passes, or a time-budgeted
// render's pass), waiting for the calling thread to hand it to `on_pass`.
struct PassImage {
  RgbImage image;
  int spp;
  double seconds;
};

py::array_t<float> toArray(const RgbImage& image) {
  py::array_t<float> out({py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(3)});
  float* data = out.mutable_data();
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    data[3 * i] = image.pixels[i].x;
    data[3 * i + 1] = image.pixels[i].y;
    data[3 * i + 2] = image.pixels[i].z;
  }
  return out;
}

// An image from a (height, width, 3) array or a file path.
RgbImage toImage(const py::object& source) {
  if (py::isinstance<py::str>(source) || py::hasattr(source, "__fspath__")) return readImage(pathOf(source));
  const FloatArray a = FloatArray::ensure(source);
  if (!a || a.ndim() != 3 || a.shape(2) != 3)
    throw UsageError("an image must be a path or an array of shape (height, width, 3)");
  RgbImage image;
  image.height = int(a.shape(0));
  image.width = int(a.shape(1));
  image.pixels.resize(size_t(image.width) * size_t(image.height));
  const float* data = a.data();
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = Color(data[3 * i], data[3 * i + 1], data[3 * i + 2]);
  return image;
}

// Keyword argument value -> option text as a command line gives it.
std::string optionText(const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    std::string out;
    for (const py::handle& v : value) out += (out.empty() ? "" : ",") + optionText(v);
    return out;
  }
  if (py::isinstance<py::float_>(value)) return py::repr(value).cast<std::string>();
  return py::str(value).cast<std::string>();
}

std::string typeNameOf(const py::handle& value) { return py::str(py::type::of(value).attr("__name__")).cast<std::string>(); }

// A common integer option: a Python int (not a bool) within `range`, refused as the CLI refuses it.
long long integerOption(const std::string& name, const py::handle& value, CommonOptionRange range) {
  char allowed[96];
  std::snprintf(allowed, sizeof allowed, "an integer in [%.0f, %.0f]", range.low, range.high);
  if (py::isinstance<py::bool_>(value) || !py::isinstance<py::int_>(value))
    throw OptionTypeError(name + " must be " + allowed + ", not " + py::repr(value).cast<std::string>() + " (" +
                          typeNameOf(value) + ")");
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
  if (overflow != 0 || double(v) < range.low || double(v) > range.high)
    throw OptionValueError(name + " must be " + allowed + ", not " + py::repr(value).cast<std::string>());
  return v;
}

// The options every integrator takes, as keyword arguments; None leaves an option unset.
RenderRequest requestOf(const std::string& integrator, const py::kwargs& options) {
  RenderRequest r;
  r.integrator = integrator;
  for (const auto& [key, value] : options) {
    const std::string name = key.cast<std::string>();
    std::string flag = name;
    std::replace(flag.begin(), flag.end(), '_', '-');
    flag = "--" + flag;
    if (value.is_none()) continue;
    if (name == "spp") r.spp = int(integerOption(name, value, kSppRange));
    else if (name == "width") r.width = int(integerOption(name, value, kImageSizeRange));
    else if (name == "height") r.height = int(integerOption(name, value, kImageSizeRange));
    else if (name == "threads") r.threads = int(integerOption(name, value, kThreadsRange));
    else if (name == "max_depth") r.maxDepth = int(integerOption(name, value, kMaxDepthRange));
    else if (name == "seed") {
      if (py::isinstance<py::bool_>(value) || !py::isinstance<py::int_>(value))
        throw OptionTypeError("seed must be an integer in [0, 2^64 - 1], not " + py::repr(value).cast<std::string>() +
                              " (" + typeNameOf(value) + ")");
      const unsigned long long seed = PyLong_AsUnsignedLongLong(value.ptr());
      if (PyErr_Occurred()) {
        PyErr_Clear();
        throw OptionValueError("seed must be an integer in [0, 2^64 - 1], not " + py::repr(value).cast<std::string>());
      }
      r.seed = seed;
    } else if (name == "time") {
      if (py::isinstance<py::bool_>(value) || !(py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)))
        throw OptionTypeError("time must be a number of seconds, not " + py::repr(value).cast<std::string>() + " (" +
                              typeNameOf(value) + ")");
      r.time = value.cast<double>();
      if (!(r.time >= kTimeRange.low && r.time <= kTimeRange.high))
        throw OptionValueError("time must be in [0.001, 1e7] seconds, not " + py::repr(value).cast<std::string>());
    } else if (name == "filter") {
      if (!py::isinstance<py::str>(value))
        throw OptionTypeError("filter must be 'box', 'tent' or 'gaussian', not " + py::repr(value).cast<std::string>());
      r.filter = value.cast<std::string>();
      if (r.filter != "box" && r.filter != "tent" && r.filter != "gaussian")
        throw OptionValueError("filter must be 'box', 'tent' or 'gaussian', not '" + r.filter + "'");
    }
    else if (std::find(kSamplePassOptions.begin(), kSamplePassOptions.end(), flag) != kSamplePassOptions.end())
      throw UsageError("'" + name + "' is an option of the command line only (erpt render " + flag + ")");
    else if (integratorsUsing(flag).empty())
      throw UsageError("unknown option '" + name + "' (the integrators' options are those of `erpt render --help`, "
                       "dashes as underscores)");
    else if (py::isinstance<py::bool_>(value) && !value.cast<bool>())
      continue;  // a flag set to False: not given
    else
      r.options.emplace_back(flag.substr(2), optionText(value));
    r.given.push_back(flag);
  }
  return r;
}

py::dict statsOf(const RenderSettings& s, const RenderStats& stats) {
  py::dict d;
  d["integrator"] = s.integrator;
  d["width"] = s.width;
  d["height"] = s.height;
  d["spp"] = stats.spp;
  d["passes"] = stats.passes;
  d["seconds"] = stats.seconds;
  d["samples"] = stats.samples;
  d["rays"] = stats.rays;
  d["rays_per_second"] = stats.seconds > 0 ? double(stats.rays) / stats.seconds : 0.0;
  d["invalid_samples"] = stats.invalidSamples;
  d["refused_rays"] = stats.refusedRays;
  d["partial"] = stats.partial;
  d["kept_spp"] = stats.keptSpp;
  py::dict stages;
  for (const auto& [name, seconds] : stats.stages.all()) stages[py::str(name)] = seconds;
  d["stage_seconds"] = stages;
  if (s.integrator == "erpt" || s.integrator == "pmc-er" || s.integrator == "mlt") {
    const ChainStats& e = chainStatsOf(const_cast<RenderStats&>(stats));
    d["chains"] = e.chains;
    d["mutations"] = e.mutations;
    py::dict proposed, accepted;
    for (int k = 1; k < kMutationKindCount; ++k) {
      if (e.proposed[k] == 0) continue;
      proposed[mutationName(MutationKind(k))] = e.proposed[k];
      accepted[mutationName(MutationKind(k))] = e.accepted[k];
    }
    d["proposed"] = proposed;
    d["accepted"] = accepted;
    py::dict inPlace, rejected;
    for (int r = 0; r < kInPlaceReasonCount; ++r) inPlace[inPlaceReasonName(InPlaceReason(r))] = e.inPlace[r];
    for (int r = 1; r < kRejectReasonCount; ++r) rejected[rejectReasonName(RejectReason(r))] = e.rejected[r];
    d["in_place"] = inPlace;
    d["rejected"] = rejected;
  }
  if (s.integrator == "pssmlt" || s.integrator == "mmlt") {
    const PssmltStats& p = pssmltStatsOf(const_cast<RenderStats&>(stats));
    d["chains"] = p.chains;
    d["mutations"] = p.smallSteps + p.largeSteps;
    py::dict proposed, accepted;
    proposed["small step"] = p.smallSteps, accepted["small step"] = p.smallAccepted;
    proposed["large step"] = p.largeSteps, accepted["large step"] = p.largeAccepted;
    d["proposed"] = proposed;
    d["accepted"] = accepted;
    d["b"] = p.b;
  }
  return d;
}

// Renders on a worker thread; the caller waits without the GIL and handles progress and
// signals between waits.
PyResult renderScene(const PyScene& scene, const py::object& integrator, const py::object& progress,
                     const py::object& reference, const py::object& onPass, const py::kwargs& options) {
  // No integrator: the scene's, if it is one of ours, else the default (as the CLI chooses).
  const RenderRequest request = requestOf(integrator.is_none() ? std::string() : integrator.cast<std::string>(), options);
  RenderSettings s = settingsFor(*scene.scene, request);
  checkOptionScope(request.given, {s.integrator});
  PyResult result;
  RgbImage referenceImage;
  std::vector<std::array<double, 3>> curve;
  if (!reference.is_none()) {
    const RenderSettings resolved = resolveSettings(*scene.scene, s);
    referenceImage = matchReferenceSize(toImage(reference), resolved.width, resolved.height);
    s.onPass = [&](const RgbImage& image, double seconds, int) {
      const ImageComparison c = compareImages(image, referenceImage);
      curve.push_back({seconds, c.mse, c.relMse});
    };
  }
  // on_pass: the images the worker made, delivered by the calling thread in order.
  std::mutex passMutex;
  std::vector<PassImage> passImages;
  const auto renderStart = std::chrono::steady_clock::now();
  if (!onPass.is_none()) {
    if (!PyCallable_Check(onPass.ptr())) throw UsageError("on_pass must be callable as on_pass(image, spp, seconds)");
    if (s.timeBudget > 0) {
      s.onPass = [&, curveHook = s.onPass](const RgbImage& image, double seconds, int spp) {
        if (curveHook) curveHook(image, seconds, spp);
        std::lock_guard<std::mutex> lock(passMutex);
        passImages.push_back({image, spp, seconds});
      };
    } else if (integratorNamed(s.integrator).samplePasses) {
      s.onPasses = [&](const RenderState& state, const std::function<RgbImage()>& image) {
        if (state.passesDone == 0) return;  // the state a render starts from
        RgbImage now = image();
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - renderStart).count();
        std::lock_guard<std::mutex> lock(passMutex);
        passImages.push_back({std::move(now), state.passesDone, seconds});
      };
    } else {
      throw UsageError(s.integrator + " renders in one pass (no images on the way): on_pass needs a time budget "
                       "(time=...) with it");
    }
  }
  std::atomic<bool> stop{false};
  std::atomic<double> fraction{-1.0};
  s.stop = &stop;
  s.progress = [&](double f) { fraction = f; };
  RenderStats stats;
  RgbImage image;
  std::exception_ptr failure;
  std::mutex m;
  std::condition_variable cv;
  bool done = false;
  double buildSeconds = 0;
  std::thread worker([&] {
    try {
      {
        std::lock_guard<std::mutex> lock(scene.tracer->mutex);
        if (!scene.tracer->tracer) {
          const auto start = std::chrono::steady_clock::now();
          scene.tracer->tracer = buildTracer(*scene.scene, s.threads);
          buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        }
        s.tracer = scene.tracer->tracer;
      }
      image = render(*scene.scene, s, stats);
    } catch (...) {
      failure = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(m);
    done = true;
    cv.notify_all();
  });
  bool interrupted = false;
  double reported = -1;
  std::exception_ptr callbackFailure;
  // A callback's exception stops the render and is raised; a KeyboardInterrupt that arrives
  // while a callback runs is Ctrl-C, which returns what is done.
  auto callbackFailed = [&] {
    stop = true;
    try {
      throw;
    } catch (py::error_already_set& e) {
      if (e.matches(PyExc_KeyboardInterrupt)) {
        interrupted = true;
        return;
      }
      callbackFailure = std::current_exception();
    } catch (...) {
      callbackFailure = std::current_exception();
    }
  };
  // Hands the images made so far to on_pass (a failure in it stops the render, as in progress).
  auto deliverPasses = [&] {
    std::vector<PassImage> ready;
    {
      std::lock_guard<std::mutex> lock(passMutex);
      ready.swap(passImages);
    }
    for (const PassImage& p : ready) {
      if (callbackFailure || interrupted) break;
      try {
        onPass(toArray(p.image), p.spp, p.seconds);
      } catch (...) {
        callbackFailed();
      }
    }
  };
  for (;;) {
    {
      py::gil_scoped_release release;
      std::unique_lock<std::mutex> lock(m);
      cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; });
      if (done) break;
    }
    deliverPasses();
    if (PyErr_CheckSignals() != 0) {  // KeyboardInterrupt (or another signal handler raised)
      PyErr_Clear();
      interrupted = true;
      stop = true;
    }
    const double f = fraction;
    if (!progress.is_none() && f != reported && !callbackFailure) {
      reported = f;
      try {
        progress(f);
      } catch (...) {
        callbackFailed();
      }
    }
  }
  worker.join();
  if (!failure) deliverPasses();
  // A render shorter than one wait still reports where it ended (1 when it finished).
  if (!failure && !interrupted && !progress.is_none() && fraction != reported && !callbackFailure) {
    try {
      progress(double(fraction));
    } catch (...) {
      callbackFailed();
    }
  }
  if (failure) std::rethrow_exception(failure);
  if (callbackFailure) std::rethrow_exception(callbackFailure);
  if (interrupted && stats.spp == 0 && !(stats.keptSpp > 0)) {  // stopped before anything could be kept
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }
  const RenderSettings resolved = resolveSettings(*scene.scene, s);
  result.image = std::move(image);
  result.images = std::move(stats.extraImages);
  result.stats = statsOf(resolved, stats);
  if (stats.partial) {
    const std::string note = partialRenderNote(resolved, stats) + " (stopped by an interrupt)";
    result.image.metadata.emplace_back("erpt:partial", note);
    result.stats["partial_note"] = note;
  }
  // Building the Embree scene, which the scene's first render does and later ones reuse: not
  // part of `seconds` nor of a `time` budget.
  result.stats["build_seconds"] = buildSeconds;
  for (const auto& p : curve) {
    py::dict point;
    point["seconds"] = p[0];
    point["mse"] = p[1];
    point["rel_mse"] = p[2];
    result.curve.append(point);
  }
  return result;
}

// The CLI's PNG tone mapping, as a uint8 array (height, width, 3).
py::array_t<uint8_t> toneMap(const RgbImage& image) {
  const std::vector<uint8_t> bytes = toneMapped8(image);
  py::array_t<uint8_t> out({py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(3)});
  std::copy(bytes.begin(), bytes.end(), out.mutable_data());
  return out;
}

// The image as the CLI's PNG, for notebooks (Result._repr_png_): written to a temporary file
// by the same writer and read back.
py::bytes pngOf(const PyResult& r) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path();
  const fs::path file = dir / ("erpt-repr-" + std::to_string(reinterpret_cast<uintptr_t>(&r)) + "-" +
                               std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()) + ".png");
  writePngAtomic(file.string(), r.image);
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::error_code ec;
  fs::remove(file, ec);
  return py::bytes(bytes);
}

void writeResult(const PyResult& r, const py::object& where) {
  const std::string path = pathOf(where);
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (!folder.empty() && !std::filesystem::is_directory(folder))
    throw UsageError("cannot write '" + path + "': the folder '" + folder.string() + "' does not exist");
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".png") return writePngAtomic(path, r.image);
  writeImageAtomic(path, r.image);
  if (ext == ".exr") writePngAtomic(std::filesystem::path(path).replace_extension(".png").string(), r.image);
}

py::dict diffImages(const py::object& image, const py::object& reference) {
  const RgbImage a = toImage(image), b = toImage(reference);
  const ImageComparison c = compareImages(a, b);
  auto ratio = [](float x, float y) { return y != 0 ? double(x) / double(y) : 0.0; };
  py::dict d;
  d["mse"] = c.mse;
  d["rel_mse"] = c.relMse;
  d["mean"] = py::make_tuple(c.mean.x, c.mean.y, c.mean.z);
  d["reference_mean"] = py::make_tuple(c.referenceMean.x, c.referenceMean.y, c.referenceMean.z);
  d["mean_ratio"] = py::make_tuple(ratio(c.mean.x, c.referenceMean.x), ratio(c.mean.y, c.referenceMean.y),
                                   ratio(c.mean.z, c.referenceMean.z));
  d["nonfinite_pixels"] = c.nonFinite;
  d["black_pixels"] = c.black;
  return d;
}

py::dict sceneInfo(const PyScene& ps) {
  const Scene& scene = *ps.scene;
  py::dict d;
  d["path"] = ps.path;
  d["film"] = py::make_tuple(scene.film.width, scene.film.height);
  d["spp"] = scene.integrator.spp;
  d["integrator"] = scene.integrator.type;
  d["max_depth"] = scene.integrator.maxDepth;
  d["triangles"] = scene.mesh.triangleCount();
  d["spheres"] = scene.spheres.count();
  py::list shapes, lights, materials, warnings;
  for (const ShapeInfo& s : scene.shapes) {
    py::dict shape;
    shape["type"] = s.type;
    shape["id"] = s.id;
    shape["triangles"] = s.triangleCount;
    shape["exact_sphere"] = s.sphere >= 0;
    shapes.append(shape);
  }
  for (const Emitter& e : scene.emitters) {
    py::dict light;
    light["type"] = emitterKindName(e);
    light["radiance"] = py::make_tuple(e.radiance.x, e.radiance.y, e.radiance.z);
    lights.append(light);
  }
  for (const Material& m : scene.materials) {
    py::dict material;
    material["name"] = m.name;
    material["type"] = bsdfKindName(m.kind);
    material["two_sided"] = m.twoSided;
    materials.append(material);
  }
  for (const std::string& w : scene.warnings.messages) warnings.append(w);
  d["shapes"] = shapes;
  d["lights"] = lights;
  d["materials"] = materials;
  d["warnings"] = warnings;
  return d;
}

}  // namespace
}  // namespace erpt

PYBIND11_MODULE(_erpt, m) {
  using namespace erpt;
  m.doc() = "Energy Redistribution Path Tracing: scenes, renders and images (see help(erpt))";
  errorType = PyErr_NewException("erpt.Error", PyExc_RuntimeError, nullptr);
  m.attr("Error") = py::handle(errorType);
  optionTypeErrorType = PyErr_NewException("erpt.OptionTypeError", py::make_tuple(py::handle(errorType), py::handle(PyExc_TypeError)).release().ptr(), nullptr);
  m.attr("OptionTypeError") = py::handle(optionTypeErrorType);
  optionValueErrorType = PyErr_NewException("erpt.OptionValueError", py::make_tuple(py::handle(errorType), py::handle(PyExc_ValueError)).release().ptr(), nullptr);
  m.attr("OptionValueError") = py::handle(optionValueErrorType);
  sceneWarningType = PyErr_NewException("erpt.SceneWarning", PyExc_UserWarning, nullptr);
  m.attr("SceneWarning") = py::handle(sceneWarningType);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(errorType, e.what());
    } catch (const UsageError& e) {
      PyErr_SetString(errorType, e.what());
    } catch (const OptionTypeError& e) {
      PyErr_SetString(optionTypeErrorType, e.what());
    } catch (const OptionValueError& e) {
      PyErr_SetString(optionValueErrorType, e.what());
    }
  });

  py::class_<PyScene>(m, "Scene", "A loaded Mitsuba scene (erpt.load_scene)")
      .def("info", &sceneInfo, "The scene's shapes, triangles, lights, materials and loader warnings, as a dict")
      .def_property_readonly("path", [](const PyScene& s) { return s.path; })
      .def("__repr__", [](const PyScene& s) { return "<erpt.Scene '" + s.path + "'>"; });

  py::class_<PyResult>(m, "Result", "A render: its linear image, statistics and (with a reference) error curve")
      .def_property_readonly("image", [](const PyResult& r) { return toArray(r.image); },
                             "The linear image, a float32 array of shape (height, width, 3)")
      .def_readonly("stats", &PyResult::stats, "The render's statistics (what the CLI summarises), as numbers")
      .def_property_readonly(
          "images",
          [](const PyResult& r) {
            py::dict d;
            for (const auto& [name, image] : r.images) d[py::str(name)] = toArray(image);
            return d;
          },
          "The render's other images by name, as the CLI writes them beside OUT.exr (OUT-name.exr): 'raw', 'chains' "
          "and 'proposals' with pm_filter, 'strategy' for pmc-er, 'mutations' and 'acceptance' with chain_maps")
      .def_readonly("curve", &PyResult::curve,
                    "With render(..., reference=...): {seconds, mse, rel_mse} after every pass of a time-budgeted render")
      .def("_repr_png_", &pngOf, "The image as the CLI's tone-mapped PNG (Jupyter shows a Result by it)")
      .def("write", &writeResult, py::arg("path"),
           "Writes the image as the CLI does: .exr (linear, with a tone-mapped .png beside it), .png (tone-mapped), or "
           "any format OpenImageIO writes");

  m.def(
      "load_scene",
      [](const py::object& where, const py::object& defaults, bool tessellateSpheres) {
        const std::string path = pathOf(where);
        LoadOptions load;
        load.tessellateSpheres = tessellateSpheres;
        if (!defaults.is_none())
          for (const auto& [k, v] : defaults.cast<py::dict>()) load.defines[k.cast<std::string>()] = optionText(v);
        PyScene s;
        s.path = path;
        {
          py::gil_scoped_release release;
          s.scene = std::make_shared<const Scene>(loadScene(path, load));
        }
        // The loader's warnings (an unsupported parameter, a plugin rendered differently) reach
        // Python as warnings, as the CLI prints them.
        for (const std::string& w : s.scene->warnings.messages)
          if (PyErr_WarnEx(sceneWarningType, w.c_str(), 1) != 0) throw py::error_already_set();
        return s;
      },
      py::arg("path"), py::arg("defaults") = py::none(), py::kw_only(), py::arg("tessellate_spheres") = false,
      "Loads a Mitsuba 0.6 or 3 XML scene; `defaults` overrides its <default> values as the CLI's -D name=value; "
      "`tessellate_spheres` loads sphere shapes as triangle meshes (the CLI's --tessellate-spheres)");
  m.def("render", &renderScene, py::arg("scene"), py::arg("integrator") = py::none(), py::kw_only(),
        py::arg("progress") = py::none(), py::arg("reference") = py::none(), py::arg("on_pass") = py::none(),
        "Renders `scene` with `integrator` (default: the scene's, as the CLI chooses it); every render option of the CLI is a keyword argument (dashes as "
        "underscores: spp, width, height, seed, threads, time, max_depth, filter, mutations_per_pixel, ...). "
        "`progress(fraction)` is called as the render goes; `reference` (an image or path) records the error after "
        "every pass of a time-budgeted render in Result.curve; `on_pass(image, spp, seconds)` gets the image so far after "
        "every group of sample passes (with time=..., after every pass). Ctrl-C stops the render and returns what is "
        "done (stats['partial'], stats['partial_note']; docs/python.md).");
  m.def("diff", &diffImages, py::arg("image"), py::arg("reference"),
        "Error metrics of an image against a reference (arrays or paths; a reference an integer multiple of the "
        "image's size is box-downsampled): mse, rel_mse, mean, reference_mean, mean_ratio, nonfinite_pixels, "
        "black_pixels");
  m.def("tonemap", [](const py::object& image) { return toneMap(toImage(image)); }, py::arg("image"),
        "The CLI's PNG tone mapping of a linear image (array or path): clamped to [0, 1], sRGB-encoded, as a uint8 "
        "array (height, width, 3)");
  m.def("read_image", [](const py::object& path) { return toArray(readImage(pathOf(path))); }, py::arg("path"),
        "Reads an image (EXR, PNG, any format OpenImageIO reads) as a linear float32 array (height, width, 3)");
  m.def("integrators", [] {
    std::vector<std::string> names;
    for (const IntegratorModule& i : integratorModules()) names.push_back(i.name);
    return names;
  }, "The integrators' names");
}
