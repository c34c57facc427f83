#include "core/basis/mean_value_coordinates.h"

#include <sstream>
#include <string>

#include "core/error.h"
#include "core/timer.h"
#include "core/basis/internal/mean_value_integrals.h"
#include "core/basis/internal/row_binding.h"

namespace sd {
namespace {

constexpr const char* kWhat = "mean value coordinates";

// One row: the integrals of mean_value_integrals.h, normalised. Their sum is the inside test.
class MeanValueRow : public RowEvaluator {
 public:
  MeanValueRow(const CageData& cage, const Vertices& points) : m_(cage.m), integrals_(cage), points_(points) {}
  bool evaluate(int i, double* row, PointKind& kind) override {
    const double total = integrals_.integrate(points_(i, 0), points_(i, 1), points_(i, 2), row, kind);
    if (!(total > 0.0)) return false;
    if (kind != PointKind::Regular) return true;  // delta or barycentric rows are normalised already
    const double inv_total = 1.0 / total;
    for (int j = 0; j < m_; ++j) row[j] *= inv_total;
    return true;
  }

 private:
  int m_;
  MeanValueIntegrals integrals_;
  const Vertices& points_;
};

std::string megabytes(double bytes) {
  std::ostringstream out;
  out.precision(bytes < 10e6 ? 2 : 0);
  out << std::fixed << bytes / 1e6 << " MB";
  return out.str();
}

}  // namespace

void check_weights_budget(int n, int m, const MvcOptions& options) {
  const double bytes = double(n) * double(m) * (options.single_precision ? 4.0 : 8.0);
  if (bytes <= double(options.memory_budget_bytes)) return;
  std::ostringstream message;
  message << "mean value coordinates: W (" << n << " x " << m << (options.single_precision ? " float32" : " float64")
          << ") would need " << megabytes(bytes) << ", over the memory budget of "
          << megabytes(double(options.memory_budget_bytes)) << "; use a coarser cage (fewer vertices)";
  if (!options.single_precision) message << " or float32 storage (half the size)";
  // Raising the budget helps only while W fits one allocation of this build.
  if (bytes <= double(kMaxAllocationBytes)) message << ", or raise the budget";
  else
    message << " (no budget helps: W is larger than the " << megabytes(double(kMaxAllocationBytes))
            << " one allocation of this build can have)";
  throw Error(ErrorCode::MemoryBudget, message.str());
}

BasisMatrix mean_value_coordinates(const Vertices& points, const Mesh& cage, const MvcOptions& options,
                                   MvcReport* report) {
  const Timer timer;
  const CageData data = prepare_cage(cage, kWhat);
  const int n = static_cast<int>(points.rows());
  check_weights_budget(n, data.m, options);
  check_points_finite(points, kWhat);
  MvcReport local;
  BasisMatrix W = bind_rows(
      points, data.m, options, kWhat, [&] { return std::make_unique<MeanValueRow>(data, points); }, local);
  local.evaluations = double(n) * double(data.faces());
  local.seconds = timer.ms() / 1e3;
  if (report) *report = local;
  return W;
}

Eigen::RowVectorXd mean_value_coordinates_row(const Eigen::RowVector3d& point, const Mesh& cage) {
  Vertices one(1, 3);
  one.row(0) = point;
  return mean_value_coordinates(one, cage).to_dense().row(0);
}

}  // namespace sd
