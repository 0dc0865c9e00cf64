// prism.Accelerator: a backend built over NumPy arrays, queried with arrays of rays.

#include <fmt/format.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <span>
#include <string>

#include "accel/accelerator.h"
#include "core/app/component_params.h"
#include "core/app/python_bindings.h"
#include "core/app/ray_batch.h"
#include "core/app/render_options.h"
#include "core/parallel.h"

namespace prism::python {
namespace {

/// A ray bound: a number for every ray, or an array of one per ray.
FloatArray ray_bound(const py::handle& value, const char* what, py::ssize_t rays) {
  const py::array array = py::array::ensure(value);
  if (!array || std::string("fiu").find(array.dtype().kind()) == std::string::npos) {
    throw py::type_error(fmt::format("{} must be a number or an array of numbers", what));
  }
  if (!(array.ndim() == 0 || (array.ndim() == 1 && array.shape(0) == rays))) {
    throw py::value_error(fmt::format("{} must be a number or have shape ({},)", what, rays));
  }
  return FloatArray::ensure(array);
}

/// The rays of intersect() and occluded(), with the arrays that hold them alive.
struct PyRays {
  FloatArray origins, directions, tmin, tmax;
  RayBatch batch;

  PyRays(const py::handle& o, const py::handle& d, const py::handle& near, const py::handle& far)
      : origins(float_rows(o, "origins", 3)), directions(float_rows(d, "directions", 3)) {
    if (origins.shape(0) != directions.shape(0)) {
      throw py::value_error(
          fmt::format("origins and directions must have the same shape, got ({}, "
                      "3) and ({}, 3)",
                      origins.shape(0), directions.shape(0)));
    }
    const py::ssize_t n = origins.shape(0);
    tmin = ray_bound(near, "tmin", n);
    tmax = ray_bound(far, "tmax", n);
    batch = RayBatch{.origins = {origins.data(), size_t(origins.size())},
                     .directions = {directions.data(), size_t(directions.size())},
                     .tmin = {tmin.data(), size_t(tmin.size())},
                     .tmax = {tmax.data(), size_t(tmax.size())},
                     .size = size_t(n)};
  }
};

/// A prism accelerator over one triangle mesh (geom_id 0) and optional spheres (geom_id 1),
/// which it owns: the Accelerator contract wants the geometry to outlive it.
class PyAccelerator {
 public:
  PyAccelerator(const std::string& name, const py::handle& vertices, const py::handle& indices,
                const py::handle& spheres, int threads, const py::kwargs& params)
      : name_(name), threads_(threads) {
    // The command line's order: options, then components and their parameters, then the input.
    validate_thread_count(threads);
    ParamSet set;
    for (const auto& [key, value] : params) {
      // "max_leaf_size" is this accelerator's parameter; a key with a dot is given whole.
      const std::string text = py::str(key);
      set.set(text.find('.') == std::string::npos ? name + "." + text : text, param_text(value));
    }
    accel_ = accelerator_registry().create(name, set);
    check_component_params(set, {{"accelerator", name}});
    params_ = set.to_string();

    const auto v = float_rows(vertices, "vertices", 3);
    const auto i = integer_rows(indices, "indices", 3);
    TriangleMesh mesh;
    mesh.name = "arrays";
    mesh.positions.resize(size_t(v.shape(0)));
    std::memcpy(mesh.positions.data(), v.data(), size_t(v.size()) * sizeof(float));
    mesh.triangles.resize(size_t(i.shape(0)));
    const int64_t* index = i.data();
    for (size_t k = 0; k < size_t(i.size()); ++k) {
      if (index[k] < 0 || index[k] > int64_t(std::numeric_limits<uint32_t>::max())) {
        throw py::value_error(fmt::format("indices must be in [0, 2^32), got {}", index[k]));
      }
      mesh.triangles[k / 3][int(k % 3)] = uint32_t(index[k]);
    }
    geometry_.meshes.push_back(std::move(mesh));
    if (!spheres.is_none()) {
      const auto s = float_rows(spheres, "spheres", 4);
      const float* p = s.data();
      for (py::ssize_t k = 0; k < s.shape(0); ++k, p += 4) {
        geometry_.spheres.push_back(Sphere{.center = Vec3(p[0], p[1], p[2]), .radius = p[3]});
      }
    }
    geometry_.finalize();

    py::gil_scoped_release release;
    const ThreadLimit limit(threads_);
    accel_->build(geometry_);
  }

  py::dict intersect(const py::handle& origins, const py::handle& directions,
                     const py::handle& tmin, const py::handle& tmax) const {
    const PyRays rays(origins, directions, tmin, tmax);
    const py::ssize_t n = py::ssize_t(rays.batch.size);
    py::array_t<float> t(n), u(n), v(n);
    py::array_t<int64_t> geom_id(n), prim_id(n);
    py::array_t<bool> hit(n);
    const HitArrays out{.t = {t.mutable_data(), size_t(n)},
                        .u = {u.mutable_data(), size_t(n)},
                        .v = {v.mutable_data(), size_t(n)},
                        .geom_id = {geom_id.mutable_data(), size_t(n)},
                        .prim_id = {prim_id.mutable_data(), size_t(n)},
                        .hit = {hit.mutable_data(), size_t(n)}};
    {
      py::gil_scoped_release release;
      const ThreadLimit limit(threads_);
      intersect_batch(*accel_, rays.batch, out);
    }
    py::dict result;
    result["t"] = t;
    result["u"] = u;
    result["v"] = v;
    result["geom_id"] = geom_id;
    result["prim_id"] = prim_id;
    result["hit"] = hit;
    return result;
  }

  py::array_t<bool> occluded(const py::handle& origins, const py::handle& directions,
                             const py::handle& tmin, const py::handle& tmax) const {
    const PyRays rays(origins, directions, tmin, tmax);
    py::array_t<bool> occluded(py::ssize_t(rays.batch.size));
    {
      py::gil_scoped_release release;
      const ThreadLimit limit(threads_);
      occluded_batch(*accel_, rays.batch, {occluded.mutable_data(), rays.batch.size});
    }
    return occluded;
  }

  py::dict stats() const {
    const AccelStats s = accel_->stats();
    py::dict out;
    out["build_ms"] = s.build_ms;
    out["nodes"] = s.nodes;
    out["leaves"] = s.leaves;
    out["max_depth"] = s.max_depth;
    out["bytes"] = s.bytes;
    out["sah_cost"] = s.sah_cost;
    return out;
  }

  const std::string& name() const { return name_; }
  const std::string& params() const { return params_; }
  int threads() const { return threads_; }
  size_t triangle_count() const { return geometry_.triangle_count(); }
  size_t sphere_count() const { return geometry_.spheres.size(); }

 private:
  std::string name_;
  int threads_ = 0;
  std::string params_;
  SceneGeometry geometry_;
  std::unique_ptr<Accelerator> accel_;
};

}  // namespace

void bind_accelerator(py::module_& m) {
  py::class_<PyAccelerator>(m, "Accelerator", R"(A prism accelerator built over arrays.

Accelerator(name, vertices, indices, *, spheres=None, threads=0, **params) builds the
accelerator `name` (prism.accelerators(): brute, bvh, embree) over one triangle mesh --
vertices (N x 3 numbers, rounded to float32) and indices (M x 3 integers into vertices) --
and optional spheres (S x 4: centre x, y, z and radius). params are the accelerator's --set
parameters, without its prefix (max_leaf_size=4 for bvh.max_leaf_size; True/False for
true/false) or, through **{"bvh.split": "sah"}, with it; unknown ones raise prism.Error as on
the command line. threads limits the build and every query (0: all hardware threads). The
build releases the GIL.

Triangle i of the mesh is hit as geom_id 0, prim_id i; sphere j as geom_id 1, prim_id j.)")
      .def(py::init<const std::string&, const py::handle&, const py::handle&, const py::handle&,
                    int, const py::kwargs&>(),
           py::arg("name"), py::arg("vertices"), py::arg("indices"), py::kw_only(),
           py::arg("spheres") = py::none(), py::arg("threads") = 0)
      .def("intersect", &PyAccelerator::intersect, py::arg("origins"), py::arg("directions"),
           py::arg("tmin") = 0.0f, py::arg("tmax") = std::numeric_limits<float>::infinity(),
           R"(The closest hit of every ray, as Accelerator::intersect() gives it in C++.

origins, directions: K x 3 numbers (rounded to float32; directions need not be unit length,
t is measured in their lengths); tmin, tmax: a number or K numbers (the ray hits in [tmin,
tmax]; a negative tmin counts as 0; a non-finite or zero-direction ray misses). Returns a dict
of K-arrays: "t" (float32, inf where missed), "u", "v" (float32 barycentrics: p = (1-u-v) p0 +
u p1 + v p2; 0 where missed), "geom_id", "prim_id" (int64, -1 where missed), "hit" (bool).
Runs in parallel on every thread allowed, with the GIL released.)")
      .def("occluded", &PyAccelerator::occluded, py::arg("origins"), py::arg("directions"),
           py::arg("tmin") = 0.0f, py::arg("tmax") = std::numeric_limits<float>::infinity(),
           R"(Whether each ray hits anything in [tmin, tmax]: a bool K-array equal to
intersect(...)["hit"]. Same arguments, parallelism and GIL release as intersect().)")
      .def_property_readonly("name", &PyAccelerator::name)
      .def_property_readonly("params", &PyAccelerator::params,
                             "The --set parameters it was built with, as text.")
      .def_property_readonly("threads", &PyAccelerator::threads)
      .def_property_readonly("triangle_count", &PyAccelerator::triangle_count)
      .def_property_readonly("sphere_count", &PyAccelerator::sphere_count)
      .def_property_readonly(
          "stats", &PyAccelerator::stats,
          "Build statistics: build_ms, nodes, leaves, max_depth, bytes, sah_cost (0 where they "
          "do not apply).")
      .def("__repr__", [](const PyAccelerator& a) {
        return fmt::format("prism.Accelerator('{}', {} triangles, {} spheres)", a.name(),
                           a.triangle_count(), a.sphere_count());
      });
}

}  // namespace prism::python
