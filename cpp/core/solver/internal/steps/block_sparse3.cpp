#include "core/solver/internal/steps/block_sparse3.h"

#include <utility>
#include <vector>

namespace sd {

void BlockPattern::index_columns() {
  const int n = vertex_count(), columns_n = column_count(), blocks = block_count();
  row.resize(blocks);
  column_start.assign(columns_n + 1, 0);
  for (int i = 0; i < n; ++i)
    for (int k = row_start[i]; k < row_start[i + 1]; ++k) {
      row[k] = i;
      ++column_start[column[k] + 1];
    }
  for (int j = 0; j < columns_n; ++j) column_start[j + 1] += column_start[j];
  // Counting sort by column; visiting the blocks in row order keeps each column's rows increasing.
  std::vector<int> fill(column_start.begin(), column_start.end() - 1);
  column_blocks.resize(blocks);
  for (int k = 0; k < blocks; ++k) column_blocks[fill[column[k]]++] = k;
  column_rows.resize(blocks);
  for (int e = 0; e < blocks; ++e) column_rows[e] = row[column_blocks[e]];
}

BlockSparse3::BlockSparse3(std::shared_ptr<const BlockPattern> pattern)
    : pattern_(std::move(pattern)), values_(9 * static_cast<std::size_t>(pattern_->block_count()), 0.0) {}

Eigen::SparseMatrix<double> BlockSparse3::to_sparse() const {
  const BlockPattern& p = *pattern_;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(9 * static_cast<std::size_t>(p.block_count()));
  for (int i = 0; i < p.vertex_count(); ++i)
    for (int k = p.row_start[i]; k < p.row_start[i + 1]; ++k)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) entries.emplace_back(3 * i + r, 3 * p.column[k] + c, block(k)[3 * r + c]);
  Eigen::SparseMatrix<double> out(3 * p.vertex_count(), 3 * p.column_count());
  out.setFromTriplets(entries.begin(), entries.end());
  return out;
}

}  // namespace sd
