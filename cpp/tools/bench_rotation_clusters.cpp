// The experiment behind the reduced integration's rotation-cluster rule (docs/method.md section 17.1;
// docs/benchmarks.md, "Rotation clusters"): how far one rotation per cluster of vertices moves the converged shape of
// bench_models' scene, to first order, for several choices of the rotations.
//
// The Laplacian term sums e_i = 1/2 |(S L X)_i - delta_hat_i(X)|^2. With X = W U its two squares need no vertices
// (sum_i |(S L W U)_i|^2 is U^T B U; |delta_hat_i| is constant), so only the cross term sum_i (S L X)_i .
// delta_hat_i needs an approximation, here delta_hat_i ~ R_c delta_i with one rotation R_c per cluster c of
// vertices. At the full solve's converged pose it compares three choices of R_c: the best one (Kabsch on the
// cluster's delta_i -> delta_hat_i; it needs the true delta_hat, so it is a bound), the one the solver uses (Kabsch
// on the edges of the cluster's sample's one-ring, rest -> deformed), and Kabsch on the cluster's own vertices about
// their centroid. For each: the error it makes in the cross term's gradient W^T (S L)^T (R delta - delta_hat), and
// the first-order shape error that gradient error causes, W (B + H)^-1 (its error), over the diagonal (H: the
// handle term's Gauss-Newton matrix; the volume constraint is left out). Clusters: farthest_point_clusters.
//   bench_rotation_clusters mesh.obj cage.obj [--threads T]
#include <Eigen/Cholesky>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/parallel/thread_pool.h"
#include "core/solver/deformer.h"
#include "core/solver/internal/energy/deformation_energy.h"
#include "core/solver/internal/energy/laplacian_coordinates.h"
#include "core/solver/internal/reduced/rotation_clusters.h"
#include "tools/drag_scene.h"
#include "tools/read_mesh_file.h"

using namespace sd;

namespace {

using Clusters = VertexClusters;

// Each cluster's best rotation of its vertices' delta_i onto delta_hat_i (it knows the true delta_hat: a bound).
std::vector<Eigen::Matrix3d> best_rotations(const Vertices& delta, const Vertices& delta_hat, const Clusters& c) {
  std::vector<Eigen::Matrix3d> cross(c.samples.size(), Eigen::Matrix3d::Zero());
  for (Eigen::Index i = 0; i < delta.rows(); ++i)
    cross[static_cast<size_t>(c.owner[static_cast<size_t>(i)])] += delta.row(i).transpose() * delta_hat.row(i);
  std::vector<Eigen::Matrix3d> out;
  for (const Eigen::Matrix3d& m : cross) out.push_back(best_rotation(m));
  return out;
}

// Each cluster's rotation from what a reduced solver has: its sample's one-ring edges, rest -> deformed.
std::vector<Eigen::Matrix3d> ring_rotations(const Mesh& mesh, const Vertices& X, const Clusters& c) {
  std::vector<Eigen::Matrix3d> cross(c.samples.size(), Eigen::Matrix3d::Zero());
  std::vector<int> cluster_of(static_cast<size_t>(mesh.V.rows()), -1);  // a sample's cluster, -1 elsewhere
  for (size_t k = 0; k < c.samples.size(); ++k) cluster_of[static_cast<size_t>(c.samples[k])] = static_cast<int>(k);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int corner = 0; corner < 3; ++corner) {
      const int i = mesh.F(f, corner), j = mesh.F(f, (corner + 1) % 3);
      const int k = cluster_of[static_cast<size_t>(i)];
      if (k >= 0) cross[static_cast<size_t>(k)] += (mesh.V.row(j) - mesh.V.row(i)).transpose() * (X.row(j) - X.row(i));
    }
  std::vector<Eigen::Matrix3d> out;
  for (const Eigen::Matrix3d& m : cross) out.push_back(best_rotation(m));
  return out;
}

// Each cluster's rotation from its own vertices about their centroid, rest -> deformed: linear in X, so a reduced
// solver can make its covariance from U alone (sum_i (x0_i - c0)(W_i - W_c) U, the bracket made once).
std::vector<Eigen::Matrix3d> cluster_rotations(const Vertices& X0, const Vertices& X, const Clusters& c) {
  const size_t k = c.samples.size();
  std::vector<Eigen::RowVector3d> rest(k, Eigen::RowVector3d::Zero()), now(k, Eigen::RowVector3d::Zero());
  std::vector<int> count(k, 0);
  for (Eigen::Index i = 0; i < X0.rows(); ++i) {
    const size_t o = static_cast<size_t>(c.owner[static_cast<size_t>(i)]);
    rest[o] += X0.row(i);
    now[o] += X.row(i);
    ++count[o];
  }
  std::vector<Eigen::Matrix3d> cross(k, Eigen::Matrix3d::Zero());
  for (Eigen::Index i = 0; i < X0.rows(); ++i) {
    const size_t o = static_cast<size_t>(c.owner[static_cast<size_t>(i)]);
    cross[o] += (X0.row(i) - rest[o] / count[o]).transpose() * (X.row(i) - now[o] / count[o]);
  }
  std::vector<Eigen::Matrix3d> out;
  for (const Eigen::Matrix3d& m : cross) out.push_back(best_rotation(m));
  return out;
}

// delta_i turned by its cluster's rotation.
Vertices turned(const Vertices& delta, const std::vector<Eigen::Matrix3d>& rotation, const Clusters& c) {
  Vertices out(delta.rows(), 3);
  for (Eigen::Index i = 0; i < delta.rows(); ++i)
    out.row(i) =
        (rotation[static_cast<size_t>(c.owner[static_cast<size_t>(i)])] * delta.row(i).transpose()).transpose();
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: bench_rotation_clusters mesh.obj cage.obj [--threads T]\n");
    return 2;
  }
  if (argc >= 5 && std::string(argv[3]) == "--threads") parallel::set_threads(std::atoi(argv[4]));
  try {
    const Mesh mesh = tools::read_mesh_file(argv[1]), cage = tools::read_mesh_file(argv[2]);
    Deformer d(mesh, cage);
    if (!d.layout().identity()) throw std::runtime_error("the mesh needs welding or splitting; not handled here");
    const tools::DragScene scene = tools::drag_scene(mesh);
    d.set_handles(scene.groups);
    d.set_targets(scene.targets(1.0));
    const StepResult solve = d.solve();
    // The energy's own terms at the converged pose (S is folded into L and delta_hat: deformation_energy.h).
    DeformationEnergy energy(mesh.V, mesh.F);
    std::vector<int> held, sizes;
    for (const auto& group : scene.groups) {
      held.insert(held.end(), group.begin(), group.end());
      sizes.push_back(static_cast<int>(group.size()));
    }
    energy.set_handles(held, sizes);
    const Eigen::SparseMatrix<double>& SL = energy.laplacian();
    const Vertices delta_hat = energy.coordinates().evaluate(d.positions());
    const Vertices delta = energy.coordinates().evaluate(mesh.V);
    // B + H, dense (m x m), from W's rows: the subspace's Gauss-Newton matrix without the rotation terms.
    const Eigen::MatrixXd W = d.basis().to_dense();
    const Eigen::MatrixXd SLW = SL * W;
    Eigen::MatrixXd A = SLW.transpose() * SLW;
    for (size_t k = 0; k < held.size(); ++k) {
      const double w = energy.handle_row_weights()[static_cast<Eigen::Index>(k)];
      A += w * w * W.row(held[k]).transpose() * W.row(held[k]);
    }
    const Eigen::LLT<Eigen::MatrixXd> A_factor(A);
    const double diagonal = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
    const Eigen::MatrixXd cross = SLW.transpose() * delta_hat;  // the cross term's gradient, m x 3
    auto report = [&](const char* what, const Vertices& approximation) {
      const Eigen::MatrixXd error = SLW.transpose() * approximation - cross;
      const double shape = (W * A_factor.solve(error)).rowwise().norm().maxCoeff() / diagonal;
      std::printf("{\"clusters\": \"%s\", \"crossTermError\": %.3g, \"shapeError\": %.3g}\n", what,
                  error.norm() / cross.norm(), shape);
    };
    std::printf("{\"n\": %d, \"m\": %d, \"converged\": %s, \"iterations\": %zu}\n", static_cast<int>(mesh.V.rows()),
                static_cast<int>(W.cols()), solve.converged ? "true" : "false", solve.iterations.size());
    report("none (R = I)", delta);
    for (int k : {100, 400, 800, 1600, 3200}) {
      if (k > mesh.V.rows()) break;
      const Clusters clusters = farthest_point_clusters(mesh.V, k);
      report((std::to_string(k) + ", best rotations").c_str(),
             turned(delta, best_rotations(delta, delta_hat, clusters), clusters));
      report((std::to_string(k) + ", from the samples' one-rings").c_str(),
             turned(delta, ring_rotations(mesh, d.positions(), clusters), clusters));
      report((std::to_string(k) + ", from the clusters' vertices").c_str(),
             turned(delta, cluster_rotations(mesh.V, d.positions(), clusters), clusters));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_rotation_clusters: %s\n", e.what());
    return 1;
  }
  return 0;
}
