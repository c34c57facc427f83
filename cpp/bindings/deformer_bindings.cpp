// The Deformer session for JS (class DeformerSession). Wrapped by web/lib/deformer.js, which
// validates argument types, lengths and index ranges before they get here; every method still runs in
// `guarded`, so any C++ failure reaches JS as an Error with the C++ message.
#include <emscripten/bind.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "bindings/convert.h"
#include "core/solver/deformer.h"

namespace sd::bindings {
namespace {

Method method_from(const std::string& name) {
  if (name == "subspace") return Method::Subspace;
  if (name == "full") return Method::Full;
  if (name == "arap") return Method::Arap;
  throw Error("method must be 'subspace', 'full' or 'arap' (got '" + name + "')");
}
const char* method_name(Method m) {
  return m == Method::Subspace ? "subspace" : m == Method::Full ? "full" : "arap";
}
JacobianMode jacobian_from(const std::string& name) {
  if (name == "exact") return JacobianMode::Exact;
  if (name == "fast") return JacobianMode::Fast;
  throw Error("jacobian must be 'exact' or 'fast' (got '" + name + "')");
}

bool present(const val& v) { return !v.isUndefined() && !v.isNull(); }

double number(const val& v, const char* name) {
  if (v.typeOf().as<std::string>() != "number") throw Error(std::string(name) + " must be a number");
  return v.as<double>();
}

val stats_to_js(const IterationStats& s) {
  val out = val::object();
  out.set("iteration", s.iteration);
  out.set("merit", s.merit);
  out.set("energy", s.energy);
  out.set("laplacianEnergy", s.laplacian_energy);
  out.set("positionEnergy", s.position_energy);
  out.set("volume", s.volume);
  out.set("volumeRelError", s.volume_rel_error);
  out.set("lambda", s.lambda);
  out.set("step", s.step);
  out.set("lineSearchTrials", s.line_search_trials);
  out.set("innerIterations", s.inner_iterations);
  out.set("products", s.products);
  out.set("passes", s.passes);
  out.set("fallbacks", s.fallbacks);
  out.set("ms", s.ms);
  return out;
}

val result_to_js(const StepResult& r) {
  val iterations = val::array();
  for (const IterationStats& s : r.iterations) iterations.call<void>("push", stats_to_js(s));
  val out = val::object();
  out.set("iterations", iterations);
  out.set("converged", r.converged);
  out.set("stopReason", r.stop_reason);
  return out;
}

class DeformerSession {
 public:
  explicit DeformerSession(std::unique_ptr<Deformer> d) : d_(std::move(d)) {}

  void set_options(const val& o) {
    guarded([&] {
      SolverOptions next = d_->options();
      if (present(o["method"])) next.method = method_from(o["method"].as<std::string>());
      if (present(o["jacobian"])) next.jacobian = jacobian_from(o["jacobian"].as<std::string>());
      if (present(o["volume"])) next.volume = o["volume"].as<bool>();
      if (present(o["positionWeight"])) next.position_weight = number(o["positionWeight"], "positionWeight");
      if (present(o["c1"])) next.armijo_c1 = number(o["c1"], "c1");
      if (present(o["c2"])) next.armijo_c2 = number(o["c2"], "c2");
      if (present(o["maxIterations"])) next.max_iterations = static_cast<int>(number(o["maxIterations"], "maxIterations"));
      if (present(o["stepTolerance"])) next.step_tolerance = number(o["stepTolerance"], "stepTolerance");
      if (present(o["meritTolerance"])) next.merit_tolerance = number(o["meritTolerance"], "meritTolerance");
      if (present(o["cgTolerance"])) next.cg_tolerance = number(o["cgTolerance"], "cgTolerance");
      if (present(o["arapEnergyTolerance"]))
        next.arap_energy_tolerance = number(o["arapEnergyTolerance"], "arapEnergyTolerance");
      if (present(o["cgMaxIterations"]))
        next.cg_max_iterations = static_cast<int>(number(o["cgMaxIterations"], "cgMaxIterations"));
      if (present(o["cgMemory"])) next.cg_memory = static_cast<int>(number(o["cgMemory"], "cgMemory"));
      if (present(o["arapAcceleration"]))
        next.arap_acceleration = static_cast<int>(number(o["arapAcceleration"], "arapAcceleration"));
      d_->set_options(next);
    });
  }

  val options() const {
    return guarded([&] {
      const SolverOptions& o = d_->options();
      val out = val::object();
      out.set("method", std::string(method_name(o.method)));
      out.set("jacobian", std::string(o.jacobian == JacobianMode::Exact ? "exact" : "fast"));
      out.set("volume", o.volume);
      out.set("positionWeight", o.position_weight);
      out.set("c1", o.armijo_c1);
      out.set("c2", o.armijo_c2);
      out.set("maxIterations", o.max_iterations);
      out.set("stepTolerance", o.step_tolerance);
      out.set("meritTolerance", o.merit_tolerance);
      out.set("cgTolerance", o.cg_tolerance);
      out.set("cgMaxIterations", o.cg_max_iterations);
      out.set("cgMemory", o.cg_memory);
      out.set("arapEnergyTolerance", o.arap_energy_tolerance);
      out.set("arapAcceleration", o.arap_acceleration);
      return out;
    });
  }

  // groups: an array of arrays of vertex indices.
  void set_handles(const val& groups) {
    guarded([&] {
      std::vector<std::vector<int>> out;
      const unsigned count = groups["length"].as<unsigned>();
      for (unsigned g = 0; g < count; ++g) {
        const val group = groups[g];
        const unsigned size = group["length"].as<unsigned>();
        std::vector<int> vertices(size);
        for (unsigned k = 0; k < size; ++k) vertices[k] = static_cast<int>(group[k].as<double>());
        out.push_back(std::move(vertices));
      }
      d_->set_handles(out);
    });
  }

  void set_targets(const val& targets) { guarded([&] { d_->set_targets(vertices_from_js(targets, "targets")); }); }
  val step(int k) { return guarded([&] { return result_to_js(d_->step(k)); }); }
  val solve() { return guarded([&] { return result_to_js(d_->solve()); }); }
  void reset() { guarded([&] { d_->reset(); }); }
  val positions() const { return guarded([&] { return to_js(d_->positions()); }); }
  val cage_positions() const { return guarded([&] { return to_js(d_->cage_positions()); }); }
  double rest_volume() const { return d_->rest_volume(); }
  double bind_ms() const { return d_->bind_ms(); }
  double precompute_ms() const { return d_->precompute_ms(); }
  int vertex_count() const { return static_cast<int>(d_->rest_mesh().V.rows()); }
  int cage_vertex_count() const { return static_cast<int>(d_->rest_cage().V.rows()); }
  int fallback_count() const { return d_->fallback_count(); }

 private:
  std::unique_ptr<Deformer> d_;
};

// new DeformerSession(meshPositions, meshIndices, cagePositions | null, cageIndices | null,
//                     { float32?, memoryBudgetMB? }, onProgress?: (fraction) => boolean | void)
// onProgress returning false cancels the binding (Error "... cancelled").
DeformerSession* make_session(val mesh_positions, val mesh_indices, val cage_positions, val cage_indices, val options,
                              val progress) {
  return guarded([&] {
    const Mesh mesh = mesh_from_js(mesh_positions, mesh_indices, "mesh");
    Mesh cage{Vertices(0, 3), Faces(0, 3)};
    if (present(cage_positions)) cage = mesh_from_js(cage_positions, cage_indices, "cage");
    MvcOptions bind;
    if (present(options) && options.typeOf().as<std::string>() == "object") {
      if (present(options["float32"])) bind.single_precision = options["float32"].as<bool>();
      if (present(options["memoryBudgetMB"])) {
        const double mb = number(options["memoryBudgetMB"], "memoryBudgetMB");
        if (!(mb > 0) || !std::isfinite(mb)) throw Error("memoryBudgetMB must be a positive number");
        bind.memory_budget_bytes = static_cast<std::size_t>(mb * 1e6);
      }
    }
    if (progress.typeOf().as<std::string>() == "function")
      bind.progress = [&progress](double fraction) { return !progress(fraction).strictlyEquals(val(false)); };
    return new DeformerSession(std::make_unique<Deformer>(mesh, cage, bind));
  });
}

}  // namespace
}  // namespace sd::bindings

EMSCRIPTEN_BINDINGS(deformer) {
  using namespace sd::bindings;
  emscripten::class_<DeformerSession>("DeformerSession")
      .constructor(&make_session)
      .function("setOptions", &DeformerSession::set_options)
      .function("options", &DeformerSession::options)
      .function("setHandles", &DeformerSession::set_handles)
      .function("setTargets", &DeformerSession::set_targets)
      .function("step", &DeformerSession::step)
      .function("solve", &DeformerSession::solve)
      .function("reset", &DeformerSession::reset)
      .function("positions", &DeformerSession::positions)
      .function("cagePositions", &DeformerSession::cage_positions)
      .function("restVolume", &DeformerSession::rest_volume)
      .function("bindMs", &DeformerSession::bind_ms)
      .function("precomputeMs", &DeformerSession::precompute_ms)
      .function("vertexCount", &DeformerSession::vertex_count)
      .function("cageVertexCount", &DeformerSession::cage_vertex_count)
      .function("fallbackCount", &DeformerSession::fallback_count);
}
