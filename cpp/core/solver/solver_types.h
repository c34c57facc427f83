// Options and per-iteration statistics shared by every deformation method behind the Deformer session.
#pragma once

#include <string>
#include <vector>

namespace sd {

enum class Method { Subspace, Full, Arap };
enum class JacobianMode { Exact, Fast };
// How the energy weights its terms (solver/internal/energy/energy_weighting.h): by area, so that the answer converges
// under refinement, or uniformly, as the original report did.
enum class EnergyWeighting { Area, Uniform };
// How the subspace method sums the Laplacian term: over every vertex, or by a reduced rule that needs no pass over W
// (solver/internal/reduced/reduced_laplacian_term.h: rotation clusters), so an iteration's cost no longer grows with
// the mesh.
enum class Integration { Full, Reduced };
// The fast subspace step's base preconditioner (docs/method.md section 11.1): the constant N = W^T (L^T L + handles) W
// plus, when it pays for itself, a kept factor of N with the stiffest vertices' rotation terms; or N alone.
enum class Preconditioner { GaussNewton, Constant };

struct SolverOptions {
  Method method = Method::Subspace;
  JacobianMode jacobian = JacobianMode::Fast;
  bool volume = true;  // hard volume constraint psi(X) = psi(X0)
  EnergyWeighting weighting = EnergyWeighting::Area;
  Integration integration = Integration::Full;  // subspace method only; the others always sum every vertex
  Preconditioner preconditioner = Preconditioner::GaussNewton;  // fast subspace step only
  double position_weight = 1.0;      // w_pos in f = [L X - delta_hat(X); w_pos (Phi X - V_hat)]
  double straightness_weight = 0.0;  // w_s: the bones' samples pulled onto their segments (docs/method.md 5.4)
  double armijo_c1 = 1e-4;           // sufficient-decrease constant (docs/method.md section 7)
  double armijo_c2 = 0.5;            // backtracking factor: alpha <- c2 alpha
  int max_iterations = 100;          // cap for solve-to-convergence calls
  double step_tolerance = 1e-7;      // stop when |alpha h| < step_tolerance * bounding-box diagonal
  double merit_tolerance = 1e-10;    // stop when the merit decreases by less than this, relatively
  // ARAP (local-global, linear convergence): stop when an iteration lowers the ARAP energy by less than
  // this, relatively (besides the step tolerance, which its slow tail rarely reaches).
  double arap_energy_tolerance = 1e-5;
  // ARAP: Anderson acceleration over this many iterations (anderson_acceleration.h); 0 = plain local-global.
  int arap_acceleration = 5;
  double cg_tolerance = 3e-2;  // fast mode: relative residual of the inner PCG
  int cg_max_iterations = 50;
  // Fast subspace mode: how many (direction, product) pairs of the previous PCG runs update the
  // preconditioner N^-1 by limited-memory BFGS (lbfgs_preconditioner.h); 0 uses N^-1 alone. 150: real cages
  // (300-400 vertices) keep learning up to about that many (the boy's products per iteration 20.5 -> 9.5 from 32,
  // its drag frames 2 -> 1).
  int cg_memory = 150;
  // Cage subspace: weight of the cage regularisation relative to the mesh energy's Hessian (docs/method.md
  // section 6.1; cage_regularization.h); 0 turns it off.
  double cage_regularization = 1e-3;
  // Exact mode forms the dense 3n x 3m subspace Jacobian; refuse (sd::Error) above this many bytes.
  double exact_memory_budget_bytes = 1e9;
};

// One trial of the Armijo line search (docs/method.md section 7), in the order tried.
struct LineSearchTrial {
  double alpha = 0;                  // the step length tried
  double merit = 0;                  // the merit at X + alpha dx (before volume restoration)
  bool sufficient_decrease = false;  // it passed the Armijo test
  bool restored = false;             // and its volume could be restored, the restored point passing the Armijo
                                     // test too (the trial was accepted)
};

// Above this test error (relative, on held-out poses) a reduced integration's rule is not reliable. Measured on
// the real models of the test data (docs/method.md section 17): the rules that tested at 0.13 or less converged
// within 3e-3 of the diagonal of the full shapes; the one at 0.56 (the hand bones) 7.8e-3 away. A reliable rule's
// matrix also serves the finishing iterations of a reduced solve (section 17.3); an unreliable one's does not.
constexpr double kReducedTestErrorLimit = 0.25;

struct IterationStats {
  int iteration = 0;  // counted from the last reset
  double merit = 0;   // 1/2 |f|^2 + cage regularisation + lambda g  (ARAP: its energy)
  double energy = 0;  // 1/2 |f|^2             (ARAP: its energy)
  double laplacian_energy = 0;
  double position_energy = 0;
  double straightness_energy = 0;    // the bones' soft straightness term (straightness_weight); else 0
  double regularization_energy = 0;  // the cage subspace's regulariser R(P) (cage_regularization.h); else 0
  double volume = 0;
  double volume_rel_error = 0;  // (psi(X) - psi(X0)) / psi(X0)
  double lambda = 0;            // the volume multiplier (with K > 1 volume parts: 0, see part_lambda)
  // With volume parts: each part's (V_k(X) - V_k(X0)) / |V_k(X0)| and multiplier (empty without parts).
  std::vector<double> part_volume_change;
  std::vector<double> part_lambda;
  // With a skeleton (skeleton_constraints.h): the largest relative bone length error |l_b - L_b| / L_b, the
  // largest straightness error (a sample's distance from its bone's segment / L_b), and each bone's length
  // multiplier (empty without a skeleton).
  double bone_length_error = 0;
  double bone_straightness_error = 0;
  std::vector<double> bone_lambda;
  double step = 0;  // |X_k - X_{k-1}| (max-norm over vertices)
  // What the iteration did, for a student stepping through it (Gauss-Newton only; zeros and empty for ARAP):
  double merit_start = 0;  // the merit at the start of the iteration, with this step's lambda
  double slope = 0;        // d/d alpha of the merit along the step at alpha = 0 (< 0: a descent direction)
  double step_length = 0;  // largest vertex move of the full Gauss-Newton step (alpha = 1)
  double alpha = 0;        // the accepted step length (0: no step taken)
  std::vector<LineSearchTrial> line_search;
  int line_search_trials = 0;
  int inner_iterations = 0;  // CG iterations (fast) or 0
  int products = 0;          // matrix-free products W^T J^T J W v this iteration (fast subspace)
  int passes = 0;            // streams over W this iteration (subspace; a product is two, batched)
  int samples = 0;           // reduced integration: the vertices its rule reads (0: full integration)
  bool finishing = false;    // reduced integration: an iteration on the energy of every vertex after the rule's
                             // converged (docs/method.md section 17.3; samples 0)
  int fallbacks = 0;         // fast mode: steps where inexact CG gave no descent direction and the
                             // preconditioned gradient step was used instead; ARAP: 1 when the Anderson
                             // extrapolation was rejected and the plain local-global step taken
  double ms = 0;
};

// Why a step() or solve() call returned. The names (stop_code_name) reach JS as result.stop; code that
// reacts to a stop reads this, never the text.
enum class StopCode {
  NoIterations,      // step(0): nothing was asked
  NoHandles,         // no handles: the rest pose is the minimizer (converged)
  StepTolerance,     // converged: the step is below step_tolerance x the bounding-box diagonal
  NoDescent,         // converged: the Gauss-Newton direction is not a descent direction
  NoDecrease,        // converged: the line search found no decrease above the step tolerance
  MeritTolerance,    // converged: the merit decreased by less than merit_tolerance, relatively
  ArapEnergy,        // converged: the ARAP energy decreased by less than arap_energy_tolerance
  IterationLimit,    // step(k) did its k iterations without converging
  MaxIterations,     // solve() reached max_iterations without converging
  NumericalFailure,  // a non-finite energy, step or iterate; the last good iterate is kept
  Stalled,           // not converged: the merit cannot be lowered although the model predicts a decrease
};

const char* stop_code_name(StopCode code);    // "step_tolerance", ...: the spelling JS sees
const char* stop_code_reason(StopCode code);  // "converged: step below tolerance", ...: for people
bool stop_code_converged(StopCode code);      // true for the codes that mean "converged"
const std::vector<StopCode>& all_stop_codes();

struct StepResult {
  std::vector<IterationStats> iterations;
  bool converged = false;
  StopCode stop = StopCode::NoIterations;
  std::string stop_reason;  // for people: stop_code_reason(stop), or a more specific text
  bool finished = false;    // finish() was called

  bool stopped() const { return finished; }

  // Records why the call stopped: stop, converged (from the code) and the reason (the code's standard
  // text unless `reason` says more).
  void finish(StopCode code, std::string reason = {}) {
    stop = code;
    converged = stop_code_converged(code);
    stop_reason = reason.empty() ? stop_code_reason(code) : std::move(reason);
    finished = true;
  }
};

}  // namespace sd
