#include "sim/solver/supernodal_ldlt.hpp"

#include <cholmod.h>
#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

extern "C" {
// BLAS (the system's: OpenBLAS where installed), Fortran calling convention.
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
            const double* alpha, const double* a, const int* lda, const double* b, const int* ldb,
            const double* beta, double* c, const int* ldc);
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m,
            const int* n, const double* alpha, const double* a, const int* lda, double* b,
            const int* ldb);
}

namespace ligsim::sim {

namespace {

/// Columns per panel of the dense factorisation inside a supernode.
constexpr int panel_width = 32;
/// Cost model of a factorisation, in units of one factor entry read by a triangular solve:
/// per flop of the dense blocks, per update entry scattered into an ancestor, and per update
/// (a BLAS call and its bookkeeping). Fitted to single-threaded timings of the FEBio cube
/// (13,872 DOFs: factorisation 72 ms, solve 3.3 ms) and the 6,141-tet MCL (4,251 DOFs: 1.8 and
/// 0.18 ms).
constexpr double cost_per_flop = 0.05;
constexpr double cost_per_update_entry = 1.0;
constexpr double cost_per_update = 2000.0;

/// C = alpha A B^T + beta C; A m x k, B n x k, C m x n (column-major).
void gemm_nt(int m, int n, int k, double alpha, const double* A, int lda, const double* B, int ldb,
             double beta, double* C, int ldc)
{
  const char no = 'N', yes = 'T';
  dgemm_(&no, &yes, &m, &n, &k, &alpha, A, &lda, B, &ldb, &beta, C, &ldc);
}

/// Makes OpenBLAS (where it is the system's BLAS) run on the calling thread. The blocks here are
/// small to medium (at most a few hundred columns): its worker threads cost more in hand-offs,
/// and in spinning on the cores the element loops need, than they gain (FEBio cube: 84 ms per
/// factorisation on one thread against 115-200 ms on two; 6,141-tet MCL: 1.7 against 7.7 ms).
void single_threaded_blas()
{
  static const bool done = [] {
    using SetThreads = void (*)(int);
    if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads")))
      set(1);
    return true;
  }();
  (void)done;
}

} // namespace

void SupernodalLdlt::analyze(const Eigen::SparseMatrix<double>& lower)
{
  single_threaded_blas();
  cholmod_common common;
  cholmod_start(&common);
  common.print = 0;
  common.nmethods = 1;
  common.method[0].ordering = CHOLMOD_METIS; // less fill than AMD on 3-D meshes
  common.supernodal = CHOLMOD_SUPERNODAL;
  cholmod_sparse A{};
  A.nrow = A.ncol = static_cast<std::size_t>(lower.rows());
  A.nzmax = static_cast<std::size_t>(lower.nonZeros());
  A.p = const_cast<int*>(lower.outerIndexPtr());
  A.i = const_cast<int*>(lower.innerIndexPtr());
  A.x = const_cast<double*>(lower.valuePtr());
  A.stype = -1;
  A.itype = CHOLMOD_INT;
  A.xtype = CHOLMOD_REAL;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;
  cholmod_factor* L = cholmod_analyze(&A, &common);
  if (!L || !L->is_super) {
    if (L)
      cholmod_free_factor(&L, &common);
    cholmod_finish(&common);
    throw std::runtime_error("sparse L D L^T: the symbolic analysis failed (out of memory?)");
  }
  const int n = static_cast<int>(L->n);
  const int supernodes = static_cast<int>(L->nsuper);
  const auto* perm = static_cast<const int*>(L->Perm);
  const auto* super = static_cast<const int*>(L->super);
  const auto* pi = static_cast<const int*>(L->pi);
  const auto* px = static_cast<const int*>(L->px);
  const auto* s = static_cast<const int*>(L->s);
  m_perm.assign(perm, perm + n);
  m_super.assign(super, super + supernodes + 1);
  m_row_start.assign(pi, pi + supernodes + 1);
  m_value_start.assign(px, px + supernodes + 1);
  m_rows.assign(s, s + L->ssize);
  m_values.assign(L->xsize, 0.0);
  m_update.resize(std::max<std::size_t>(L->maxcsize, 1));
  m_flops = common.fl;
  cholmod_free_factor(&L, &common);
  cholmod_finish(&common);

  m_column_super.resize(static_cast<std::size_t>(n));
  std::size_t widest = 1;
  for (int k = 0; k < supernodes; ++k) {
    const int width = m_super[k + 1] - m_super[k];
    widest = std::max(widest, static_cast<std::size_t>(width));
    for (int c = m_super[k]; c < m_super[k + 1]; ++c) {
      m_column_super[static_cast<std::size_t>(c)] = k;
      // A supernode's rows start with its own columns, in order.
      if (m_rows[static_cast<std::size_t>(m_row_start[k] + c - m_super[k])] != c)
        throw std::runtime_error("sparse L D L^T: unexpected supernode layout");
    }
  }
  std::size_t tallest = 1;
  for (int k = 0; k < supernodes; ++k)
    tallest = std::max(tallest, static_cast<std::size_t>(m_row_start[k + 1] - m_row_start[k]));
  m_scaled.resize(tallest * widest);
  m_tallest = static_cast<int>(tallest);

  // Where each entry of A lands in the blocks of L (in elimination order).
  std::vector<int> inverse(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k)
    inverse[static_cast<std::size_t>(m_perm[static_cast<std::size_t>(k)])] = k;
  m_scatter.resize(static_cast<std::size_t>(lower.nonZeros()));
  for (int j = 0; j < n; ++j)
    for (int p = lower.outerIndexPtr()[j]; p < lower.outerIndexPtr()[j + 1]; ++p) {
      const int a = inverse[static_cast<std::size_t>(lower.innerIndexPtr()[p])];
      const int b = inverse[static_cast<std::size_t>(j)];
      const int column = std::min(a, b);
      const int row = std::max(a, b);
      const int k = m_column_super[static_cast<std::size_t>(column)];
      const int height = m_row_start[k + 1] - m_row_start[k];
      const int width = m_super[k + 1] - m_super[k];
      int local = row - m_super[k];
      if (row >= m_super[k + 1]) {
        const int* first = m_rows.data() + m_row_start[k] + width;
        const int* last = m_rows.data() + m_row_start[k + 1];
        local = width + static_cast<int>(std::lower_bound(first, last, row) - first);
      }
      m_scatter[static_cast<std::size_t>(p)] =
          m_value_start[static_cast<std::size_t>(k)] +
          static_cast<std::ptrdiff_t>(column - m_super[k]) * height + local;
    }
  m_local_row.assign(static_cast<std::size_t>(n), 0);
  m_head.assign(static_cast<std::size_t>(supernodes), -1);
  m_next.assign(static_cast<std::size_t>(supernodes), -1);
  m_position.assign(static_cast<std::size_t>(supernodes), 0);
  m_n = n;
  m_ok = false;
  estimate_cost();
}

void SupernodalLdlt::estimate_cost()
{
  // The descendant updates of a factorisation, walked without the arithmetic.
  const int supernodes = static_cast<int>(m_super.size()) - 1;
  double updates = 0.0;
  double update_entries = 0.0;
  std::fill(m_head.begin(), m_head.end(), -1);
  auto link = [&](int d, int position) {
    const int* rows = m_rows.data() + m_row_start[d];
    if (position < m_row_start[d + 1] - m_row_start[d]) {
      m_position[static_cast<std::size_t>(d)] = position;
      const int ancestor = m_column_super[static_cast<std::size_t>(rows[position])];
      m_next[static_cast<std::size_t>(d)] = m_head[static_cast<std::size_t>(ancestor)];
      m_head[static_cast<std::size_t>(ancestor)] = d;
    }
  };
  for (int s = 0; s < supernodes; ++s) {
    for (int d = m_head[static_cast<std::size_t>(s)]; d >= 0;) {
      const int next = m_next[static_cast<std::size_t>(d)];
      const int* rows = m_rows.data() + m_row_start[d];
      const int height = m_row_start[d + 1] - m_row_start[d];
      const int first = m_position[static_cast<std::size_t>(d)];
      int last = first;
      while (last < height && rows[last] < m_super[s + 1])
        ++last;
      updates += 1.0;
      update_entries += static_cast<double>(height - first) * (last - first);
      link(d, last);
      d = next;
    }
    link(s, m_super[s + 1] - m_super[s]);
  }
  m_cost =
      cost_per_flop * m_flops + cost_per_update_entry * update_entries + cost_per_update * updates;
}

bool SupernodalLdlt::factorize(const Eigen::SparseMatrix<double>& lower)
{
  m_ok = false;
  std::fill(m_values.begin(), m_values.end(), 0.0);
  const double* a = lower.valuePtr();
  for (std::size_t p = 0; p < m_scatter.size(); ++p)
    m_values[static_cast<std::size_t>(m_scatter[p])] += a[p];
  m_pivots.resize(m_n);
  m_negative = 0;
  const int supernodes = static_cast<int>(m_super.size()) - 1;
  std::fill(m_head.begin(), m_head.end(), -1);
  for (int s = 0; s < supernodes; ++s) {
    const int first_row = m_row_start[s];
    const int height = m_row_start[s + 1] - first_row;
    for (int r = 0; r < height; ++r)
      m_local_row[static_cast<std::size_t>(m_rows[static_cast<std::size_t>(first_row + r)])] = r;
    for (int d = m_head[static_cast<std::size_t>(s)]; d >= 0;) {
      const int next = m_next[static_cast<std::size_t>(d)];
      apply_descendant(d, m_position[static_cast<std::size_t>(d)], s);
      d = next;
    }
    if (!factorize_supernode(s)) {
      m_pivots.resize(0);
      return false;
    }
    const int width = m_super[s + 1] - m_super[s];
    if (height > width) {
      m_position[static_cast<std::size_t>(s)] = width;
      const int ancestor = m_column_super[static_cast<std::size_t>(
          m_rows[static_cast<std::size_t>(first_row + width)])];
      m_next[static_cast<std::size_t>(s)] = m_head[static_cast<std::size_t>(ancestor)];
      m_head[static_cast<std::size_t>(ancestor)] = s;
    }
  }
  m_ok = true;
  return true;
}

void SupernodalLdlt::apply_descendant(int d, int first, int s)
{
  const int* rows = m_rows.data() + m_row_start[d];
  const int height = m_row_start[d + 1] - m_row_start[d];
  const int width = m_super[d + 1] - m_super[d];
  const double* L = m_values.data() + m_value_start[static_cast<std::size_t>(d)];
  const int end_column = m_super[s + 1];
  int last = first;
  while (last < height && rows[last] < end_column)
    ++last;
  const int inside = last - first; // rows of d that are columns of s
  const int below = height - first;

  // update = L_d(first:, :) D_d L_d(first:last, :)^T, below x inside.
  double* scaled = m_scaled.data();
  for (int c = 0; c < width; ++c) {
    const double pivot = L[c + static_cast<std::ptrdiff_t>(c) * height];
    const double* column = L + static_cast<std::ptrdiff_t>(c) * height + first;
    for (int r = 0; r < inside; ++r)
      scaled[r + static_cast<std::ptrdiff_t>(c) * inside] = column[r] * pivot;
  }
  if (m_update.size() < static_cast<std::size_t>(below) * static_cast<std::size_t>(inside))
    m_update.resize(static_cast<std::size_t>(below) * static_cast<std::size_t>(inside));
  double* update = m_update.data();
  gemm_nt(below, inside, width, 1.0, L + first, height, scaled, inside, 0.0, update, below);

  double* target = m_values.data() + m_value_start[static_cast<std::size_t>(s)];
  const int target_height = m_row_start[s + 1] - m_row_start[s];
  const int first_column = m_super[s];
  for (int j = 0; j < inside; ++j) {
    double* column =
        target + static_cast<std::ptrdiff_t>(rows[first + j] - first_column) * target_height;
    const double* from = update + static_cast<std::ptrdiff_t>(j) * below;
    for (int i = j; i < below; ++i)
      column[m_local_row[static_cast<std::size_t>(rows[first + i])]] -= from[i];
  }

  m_position[static_cast<std::size_t>(d)] = last;
  if (last < height) {
    const int ancestor = m_column_super[static_cast<std::size_t>(rows[last])];
    m_next[static_cast<std::size_t>(d)] = m_head[static_cast<std::size_t>(ancestor)];
    m_head[static_cast<std::size_t>(ancestor)] = d;
  }
}

bool SupernodalLdlt::factorize_supernode(int s)
{
  const int height = m_row_start[s + 1] - m_row_start[s];
  const int width = m_super[s + 1] - m_super[s];
  double* L = m_values.data() + m_value_start[static_cast<std::size_t>(s)];
  auto at = [&](int r, int c) -> double& { return L[r + static_cast<std::ptrdiff_t>(c) * height]; };
  for (int begin = 0; begin < width; begin += panel_width) {
    const int size = std::min(panel_width, width - begin);
    const int end = begin + size;
    // The panel's diagonal block, column by column (left-looking inside the panel).
    for (int j = begin; j < end; ++j) {
      for (int k = begin; k < j; ++k) {
        const double w = at(j, k) * at(k, k);
        for (int r = j; r < end; ++r)
          at(r, j) -= at(r, k) * w;
      }
      const double pivot = at(j, j);
      if (!std::isfinite(pivot) || pivot == 0.0)
        return false;
      for (int r = j + 1; r < end; ++r)
        at(r, j) /= pivot;
      m_pivots(m_super[s] + j) = pivot;
      m_negative += pivot < 0.0 ? 1 : 0;
    }
    const int rest = height - end; // rows below the panel's diagonal block
    if (rest == 0)
      continue;
    // B = A(end:, panel) L_panel^-T = L(end:, panel) D_panel.
    const char right = 'R', low = 'L', transpose = 'T', unit = 'U';
    const double one = 1.0;
    dtrsm_(&right, &low, &transpose, &unit, &rest, &size, &one, &at(begin, begin), &height,
           &at(end, begin), &height);
    const int trailing = width - end; // the supernode's columns after the panel
    double* kept = m_scaled.data();
    for (int c = begin; c < end; ++c) {
      const double inverse = 1.0 / at(c, c);
      for (int r = 0; r < trailing; ++r)
        kept[r + static_cast<std::ptrdiff_t>(c - begin) * trailing] = at(end + r, c);
      for (int r = end; r < height; ++r)
        at(r, c) *= inverse;
    }
    // Trailing columns: A(end:, end:width) -= L(end:, panel) B(end:width, panel)^T (the part
    // above the diagonal is written too, and never read).
    if (trailing > 0)
      gemm_nt(rest, trailing, size, -1.0, &at(end, begin), height, kept, trailing, 1.0,
              &at(end, end), height);
  }
  return true;
}

Eigen::VectorXd SupernodalLdlt::solve(const Eigen::VectorXd& b) const
{
  using Block = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
  Eigen::VectorXd y(m_n);
  for (int k = 0; k < m_n; ++k)
    y(k) = b(m_perm[static_cast<std::size_t>(k)]);
  Eigen::VectorXd scratch(m_tallest);
  const int supernodes = static_cast<int>(m_super.size()) - 1;
  for (int s = 0; s < supernodes; ++s) {
    const int width = m_super[s + 1] - m_super[s];
    const int height = m_row_start[s + 1] - m_row_start[s];
    const Block L(m_values.data() + m_value_start[static_cast<std::size_t>(s)], height, width,
                  Eigen::OuterStride<>(height));
    Eigen::Ref<Eigen::VectorXd> x = y.segment(m_super[s], width);
    L.topRows(width).triangularView<Eigen::UnitLower>().solveInPlace(x);
    const int below = height - width;
    if (below == 0)
      continue;
    scratch.head(below).noalias() = L.bottomRows(below) * x;
    const int* rows = m_rows.data() + m_row_start[s] + width;
    for (int r = 0; r < below; ++r)
      y(rows[r]) -= scratch(r);
  }
  y.array() /= m_pivots.array();
  for (int s = supernodes - 1; s >= 0; --s) {
    const int width = m_super[s + 1] - m_super[s];
    const int height = m_row_start[s + 1] - m_row_start[s];
    const Block L(m_values.data() + m_value_start[static_cast<std::size_t>(s)], height, width,
                  Eigen::OuterStride<>(height));
    Eigen::Ref<Eigen::VectorXd> x = y.segment(m_super[s], width);
    const int below = height - width;
    if (below > 0) {
      const int* rows = m_rows.data() + m_row_start[s] + width;
      for (int r = 0; r < below; ++r)
        scratch(r) = y(rows[r]);
      x.noalias() -= L.bottomRows(below).transpose() * scratch.head(below);
    }
    L.topRows(width).triangularView<Eigen::UnitLower>().transpose().solveInPlace(x);
  }
  Eigen::VectorXd result(m_n);
  for (int k = 0; k < m_n; ++k)
    result(m_perm[static_cast<std::size_t>(k)]) = y(k);
  return result;
}

} // namespace ligsim::sim
