// A 3#V by 3#V matrix of 3x3 blocks on a vertex adjacency pattern (row block i holds the blocks of the
// columns {i} and the one-ring of i; or some of the rows only, against the vertices they touch): the shape of the
// Laplacian rows of the energy's Jacobian, L (x) I3 - J_delta_hat (deformation_energy.h), and of the Jacobian of
// delta_hat. The solver applies those in factored form (laplacian_rows.h); this explicit form serves the exact modes
// and the tests, which need the matrix itself. Entry (3i + r, 3j + c) of the matrix is row r, column c of block (i, j).
#pragma once

#include <Eigen/Sparse>
#include <memory>
#include <vector>

namespace sd {

struct BlockPattern {
  std::vector<int> row_start;  // rows + 1: the blocks of row i are row_start[i] .. row_start[i + 1] - 1
  std::vector<int> column;     // per block: its column vertex
  // The same blocks by column (filled by index_columns()): the blocks of column j are
  // column_blocks[column_start[j] .. column_start[j + 1]), by increasing row; row[k] is block k's row.
  // A transposed product then gathers into each output vertex in the order a serial scatter over the
  // rows would add to it, so it splits over threads with the same bits (laplacian_rows.cpp).
  std::vector<int> column_start;
  std::vector<int> column_blocks;
  std::vector<int> row;
  std::vector<int> column_rows;  // row[column_blocks[e]]: the rows of the blocks in column order
  // Columns beyond the rows: a pattern of some rows only (a sampled subset of the vertices, whose one-rings are
  // the columns; LaplacianCoordinates::restricted) sets this; 0 means square, one row per vertex.
  int columns = 0;
  int vertex_count() const { return static_cast<int>(row_start.size()) - 1; }  // rows
  int column_count() const { return columns > 0 ? columns : vertex_count(); }
  int block_count() const { return static_cast<int>(column.size()); }
  void index_columns();
};

class BlockSparse3 {
 public:
  BlockSparse3() = default;
  explicit BlockSparse3(std::shared_ptr<const BlockPattern> pattern);  // all blocks zero

  const BlockPattern& pattern() const { return *pattern_; }
  bool has_pattern(const std::shared_ptr<const BlockPattern>& p) const { return pattern_ == p; }
  // Block k, 9 doubles, row-major.
  double* block(int k) { return values_.data() + 9 * static_cast<std::size_t>(k); }
  const double* block(int k) const { return values_.data() + 9 * static_cast<std::size_t>(k); }

  // As an Eigen sparse matrix (interleaved index 3 * vertex + axis): for exact modes and tests.
  Eigen::SparseMatrix<double> to_sparse() const;

 private:
  std::shared_ptr<const BlockPattern> pattern_;
  std::vector<double> values_;
};

}  // namespace sd
