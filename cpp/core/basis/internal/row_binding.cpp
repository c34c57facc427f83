#include "core/basis/internal/row_binding.h"

#include <algorithm>
#include <limits>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "core/parallel/parallel_for.h"

namespace sd {

void check_points_finite(const Vertices& points, const std::string& what) {
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    if (!points.row(i).allFinite())
      throw Error(ErrorCode::InvalidMesh, what + ": mesh vertex " + std::to_string(i) + " has non-finite coordinates");
}

BasisMatrix bind_rows(const Vertices& points, int m, const MvcOptions& options, const std::string& what,
                      const std::function<std::unique_ptr<RowEvaluator>()>& make_evaluator, MvcReport& report,
                      std::vector<double>* tallies) {
  const int n = static_cast<int>(points.rows());
  BasisMatrix W(n, m, options.single_precision);
  constexpr int kBlockRows = 256;
  struct BlockFindings {
    MvcReport report;
    std::vector<int> outside;
    std::vector<double> tallies;
  };
  auto bind_block = [&](int lo, int hi) {
    BlockFindings found;
    found.report.min_weight = std::numeric_limits<double>::infinity();
    std::unique_ptr<RowEvaluator> evaluator = make_evaluator();
    Eigen::RowVectorXd row(m);
    for (int i = lo; i < hi; ++i) {
      PointKind kind;
      if (!evaluator->evaluate(i, row.data(), kind)) {
        found.outside.push_back(i);
        continue;
      }
      if (kind == PointKind::OnVertex) ++found.report.on_vertex;
      if (kind == PointKind::OnFace) ++found.report.on_face;
      Eigen::Index col;
      const double smallest = row.minCoeff(&col);
      if (smallest < found.report.min_weight) {
        found.report.min_weight = smallest;
        found.report.min_weight_row = i;
        found.report.min_weight_col = static_cast<int>(col);
      }
      W.set_row(i, row);
    }
    found.tallies = evaluator->tallies();
    return found;
  };
  auto combine = [](BlockFindings a, BlockFindings b) {
    if (b.report.min_weight < a.report.min_weight) {  // strict: the first row in row order wins a tie
      a.report.min_weight = b.report.min_weight;
      a.report.min_weight_row = b.report.min_weight_row;
      a.report.min_weight_col = b.report.min_weight_col;
    }
    a.report.on_vertex += b.report.on_vertex;
    a.report.on_face += b.report.on_face;
    a.outside.insert(a.outside.end(), b.outside.begin(), b.outside.end());
    a.tallies.resize(std::max(a.tallies.size(), b.tallies.size()), 0.0);
    for (size_t k = 0; k < b.tallies.size(); ++k) a.tallies[k] += b.tallies[k];
    return a;
  };
  BlockFindings all;
  all.report.min_weight = std::numeric_limits<double>::infinity();
  // With a progress callback the rows go in chunks of one block per thread, reported between chunks.
  const int chunk = options.progress ? kBlockRows * parallel::threads() : std::max(n, 1);
  for (int c0 = 0; c0 < n; c0 += chunk) {
    const int c1 = std::min(n, c0 + chunk);
    all = parallel::parallel_reduce(c0, c1, kBlockRows, std::move(all), bind_block, combine);
    if (options.progress && c1 < n && !options.progress(double(c1) / n))
      throw Error(ErrorCode::Cancelled, "binding cancelled");
  }
  if (n == 0) all.report.min_weight = 0.0;
  if (!all.outside.empty()) {
    std::ostringstream message;
    message << what << ": " << all.outside.size() << " of " << n << " mesh vertices are outside the cage (first: ";
    for (size_t k = 0; k < all.outside.size() && k < 8; ++k) message << (k ? ", " : "") << all.outside[k];
    message << (all.outside.size() > 8 ? ", ...)" : ")")
            << "; every vertex must be strictly inside a closed, outward-oriented cage";
    throw Error(ErrorCode::MeshOutsideCage, message.str());
  }
  // The last call may cancel too: a mesh of few rows gets no other.
  if (options.progress && !options.progress(1.0)) throw Error(ErrorCode::Cancelled, "binding cancelled");
  report.min_weight = all.report.min_weight;
  report.min_weight_row = all.report.min_weight_row;
  report.min_weight_col = all.report.min_weight_col;
  report.on_vertex = all.report.on_vertex;
  report.on_face = all.report.on_face;
  if (tallies) *tallies = all.tallies;
  return W;
}

}  // namespace sd
