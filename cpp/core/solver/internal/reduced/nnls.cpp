#include "core/solver/internal/reduced/nnls.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace sd {
namespace {

// Minimises 1/2 w.G w - h.w over w >= 0 (G = A^T A, h = A^T b) by cyclic coordinate descent from w.
void coordinate_descent(const Eigen::MatrixXd& G, const Eigen::VectorXd& h, Eigen::VectorXd& w) {
  const Eigen::Index k = w.size();
  Eigen::VectorXd gradient = G * w - h;
  const double scale = std::max(h.cwiseAbs().maxCoeff(), 1e-300);
  for (int sweep = 0; sweep < 2000; ++sweep) {
    double largest = 0.0;
    for (Eigen::Index j = 0; j < k; ++j) {
      if (!(G(j, j) > 0.0)) continue;
      const double next = std::max(0.0, w[j] - gradient[j] / G(j, j));
      const double delta = next - w[j];
      if (delta == 0.0) continue;
      w[j] = next;
      gradient += delta * G.col(j);
      largest = std::max(largest, std::abs(delta) * G(j, j));
    }
    if (largest <= 1e-12 * scale) break;  // no coordinate moves the gradient measurably
  }
}

}  // namespace

Eigen::VectorXd nonnegative_least_squares(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  Eigen::VectorXd w = Eigen::VectorXd::Zero(A.cols());
  coordinate_descent(A.transpose() * A, A.transpose() * b, w);
  return w;
}

NnlsFit greedy_nnls(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, int max_columns, double tolerance) {
  const Eigen::Index candidates = A.cols();
  const double target = b.norm();
  const Eigen::VectorXd norms = A.colwise().norm();
  std::vector<char> chosen(static_cast<size_t>(candidates), 0);
  std::vector<int> S;
  Eigen::VectorXd w, residual = b;
  Eigen::MatrixXd G;  // A_S^T A_S, grown as columns are added
  Eigen::VectorXd h;  // A_S^T b
  while (static_cast<int>(S.size()) < max_columns && residual.norm() > tolerance * target) {
    // The candidates most positively correlated with the residual; a batch of about an eighth of those chosen
    // so far per round keeps the rounds few.
    const Eigen::VectorXd correlation = A.transpose() * residual;
    std::vector<int> order;
    for (Eigen::Index j = 0; j < candidates; ++j)
      if (!chosen[j] && norms[j] > 0.0 && correlation[j] > 0.0) order.push_back(static_cast<int>(j));
    if (order.empty()) break;
    const int batch = std::min<int>({static_cast<int>(order.size()), std::max(1, static_cast<int>(S.size()) / 8),
                                     max_columns - static_cast<int>(S.size())});
    std::partial_sort(order.begin(), order.begin() + batch, order.end(), [&](int a, int c) {
      return correlation[a] / norms[a] > correlation[c] / norms[c] ||
             (correlation[a] / norms[a] == correlation[c] / norms[c] && a < c);
    });
    const Eigen::Index old = static_cast<Eigen::Index>(S.size());
    for (int k = 0; k < batch; ++k) {
      chosen[order[k]] = 1;
      S.push_back(order[k]);
    }
    const Eigen::Index size = static_cast<Eigen::Index>(S.size());
    Eigen::MatrixXd AS(A.rows(), size);
    for (Eigen::Index k = 0; k < size; ++k) AS.col(k) = A.col(S[k]);
    Eigen::MatrixXd grown = Eigen::MatrixXd::Zero(size, size);
    grown.topLeftCorner(old, old) = G;
    grown.rightCols(size - old) = AS.transpose() * AS.rightCols(size - old);
    grown.bottomLeftCorner(size - old, old) = grown.topRightCorner(old, size - old).transpose();
    G = std::move(grown);
    h = AS.transpose() * b;
    w.conservativeResize(size);
    w.tail(size - old).setZero();
    coordinate_descent(G, h, w);
    residual = b - AS * w;
  }
  NnlsFit fit;
  std::vector<int> order(S.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int c) { return S[a] < S[c]; });
  std::vector<double> weights;
  for (int k : order)
    if (w[k] > 0.0) {
      fit.columns.push_back(S[k]);
      weights.push_back(w[k]);
    }
  fit.weights = Eigen::Map<Eigen::VectorXd>(weights.data(), static_cast<Eigen::Index>(weights.size()));
  fit.relative_error = target > 0.0 ? residual.norm() / target : 0.0;
  return fit;
}

}  // namespace sd
