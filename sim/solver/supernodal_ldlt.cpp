#include "sim/solver/supernodal_ldlt.hpp"

#include <cholmod.h>
#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
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
/// Doubles of one block of a descendant's update (taller updates go in blocks of rows).
constexpr std::size_t update_capacity = std::size_t{1} << 17;
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

/// Walks the supernodes in elimination order: for each, begin(s), update(d, first, last, s) for
/// every descendant d that updates it (d's rows [first, last) are columns of s), then finish(s);
/// false as soon as finish returns false. `head`, `next`, `position`: workspace, one per
/// supernode.
template <class Begin, class Update, class Finish>
bool walk_supernodes(const SupernodalSymbolic& symbolic, std::vector<int>& head,
                     std::vector<int>& next, std::vector<int>& position, Begin&& begin,
                     Update&& update, Finish&& finish)
{
  std::fill(head.begin(), head.end(), -1);
  // Queues d for the supernode of its row `from`, if it has one.
  auto link = [&](int d, int from) {
    const int height = symbolic.row_start[d + 1] - symbolic.row_start[d];
    if (from == height)
      return;
    const int row = symbolic.rows[static_cast<std::size_t>(symbolic.row_start[d] + from)];
    const auto ancestor =
        static_cast<std::size_t>(symbolic.column_super[static_cast<std::size_t>(row)]);
    position[static_cast<std::size_t>(d)] = from;
    next[static_cast<std::size_t>(d)] = head[ancestor];
    head[ancestor] = d;
  };
  for (int s = 0; s < symbolic.supernodes(); ++s) {
    begin(s);
    for (int d = head[static_cast<std::size_t>(s)]; d >= 0;) {
      const int following = next[static_cast<std::size_t>(d)];
      const int* rows = symbolic.rows.data() + symbolic.row_start[d];
      const int height = symbolic.row_start[d + 1] - symbolic.row_start[d];
      const int first = position[static_cast<std::size_t>(d)];
      int last = first;
      while (last < height && rows[last] < symbolic.super[s + 1])
        ++last;
      update(d, first, last, s);
      link(d, last);
      d = following;
    }
    if (!finish(s))
      return false;
    link(s, symbolic.super[s + 1] - symbolic.super[s]);
  }
  return true;
}

std::shared_ptr<SupernodalSymbolic> analyse(const Eigen::SparseMatrix<double>& lower)
{
  auto symbolic = std::make_shared<SupernodalSymbolic>();
  SupernodalSymbolic& a = *symbolic;
  a.pattern_outer.assign(lower.outerIndexPtr(), lower.outerIndexPtr() + lower.outerSize() + 1);
  a.pattern_inner.assign(lower.innerIndexPtr(), lower.innerIndexPtr() + lower.nonZeros());

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
  a.perm.assign(perm, perm + n);
  a.super.assign(super, super + supernodes + 1);
  a.row_start.assign(pi, pi + supernodes + 1);
  a.value_start.assign(px, px + supernodes + 1);
  a.rows.assign(s, s + L->ssize);
  a.value_count = L->xsize;
  a.flops = common.fl;
  cholmod_free_factor(&L, &common);
  cholmod_finish(&common);

  a.column_super.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < supernodes; ++k) {
    const int height = a.row_start[k + 1] - a.row_start[k];
    const int width = a.super[k + 1] - a.super[k];
    a.tallest = std::max(a.tallest, height);
    // The panels' kept rows (see factorize_supernode).
    a.scratch_size = std::max(a.scratch_size, static_cast<std::size_t>(width) * panel_width);
    for (int c = a.super[k]; c < a.super[k + 1]; ++c) {
      a.column_super[static_cast<std::size_t>(c)] = k;
      // A supernode's rows start with its own columns, in order.
      if (a.rows[static_cast<std::size_t>(a.row_start[k] + c - a.super[k])] != c)
        throw std::runtime_error("sparse L D L^T: unexpected supernode layout");
    }
  }

  // Where each entry of A lands in the blocks of L (in elimination order).
  std::vector<int> inverse(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k)
    inverse[static_cast<std::size_t>(a.perm[static_cast<std::size_t>(k)])] = k;
  a.scatter.resize(static_cast<std::size_t>(lower.nonZeros()));
  for (int j = 0; j < n; ++j)
    for (int p = lower.outerIndexPtr()[j]; p < lower.outerIndexPtr()[j + 1]; ++p) {
      const int first = inverse[static_cast<std::size_t>(lower.innerIndexPtr()[p])];
      const int second = inverse[static_cast<std::size_t>(j)];
      const int column = std::min(first, second);
      const int row = std::max(first, second);
      const int k = a.column_super[static_cast<std::size_t>(column)];
      const int height = a.row_start[k + 1] - a.row_start[k];
      const int width = a.super[k + 1] - a.super[k];
      int local = row - a.super[k];
      if (row >= a.super[k + 1]) {
        const int* begin = a.rows.data() + a.row_start[k] + width;
        const int* end = a.rows.data() + a.row_start[k + 1];
        local = width + static_cast<int>(std::lower_bound(begin, end, row) - begin);
      }
      a.scatter[static_cast<std::size_t>(p)] =
          a.value_start[static_cast<std::size_t>(k)] +
          static_cast<std::ptrdiff_t>(column - a.super[k]) * height + local;
    }

  // The descendant updates, walked without the arithmetic: cost and scratch space.
  double updates = 0.0;
  double update_entries = 0.0;
  std::vector<int> head(static_cast<std::size_t>(supernodes));
  std::vector<int> next(head.size());
  std::vector<int> position(head.size());
  walk_supernodes(
      a, head, next, position, [](int) {},
      [&](int d, int first, int last, int) {
        const int height = a.row_start[d + 1] - a.row_start[d];
        const int width = a.super[d + 1] - a.super[d];
        updates += 1.0;
        update_entries += static_cast<double>(height - first) * (last - first);
        a.scratch_size = std::max(a.scratch_size, static_cast<std::size_t>(last - first) * width);
      },
      [](int) { return true; });
  a.cost =
      cost_per_flop * a.flops + cost_per_update_entry * update_entries + cost_per_update * updates;
  return symbolic;
}

} // namespace

bool SupernodalSymbolic::matches(const Eigen::SparseMatrix<double>& lower) const
{
  return static_cast<std::size_t>(lower.outerSize()) + 1 == pattern_outer.size() &&
         static_cast<std::size_t>(lower.nonZeros()) == pattern_inner.size() &&
         std::equal(pattern_outer.begin(), pattern_outer.end(), lower.outerIndexPtr()) &&
         std::equal(pattern_inner.begin(), pattern_inner.end(), lower.innerIndexPtr());
}

void SupernodalLdlt::analyze(const Eigen::SparseMatrix<double>& lower)
{
  single_threaded_blas();
  static std::mutex mutex;
  static std::shared_ptr<const SupernodalSymbolic> last;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    m_symbolic = last && last->matches(lower) ? last : nullptr;
  }
  if (!m_symbolic) {
    m_symbolic = analyse(lower);
    const std::lock_guard<std::mutex> lock(mutex);
    last = m_symbolic;
  }
  const SupernodalSymbolic& a = *m_symbolic;
  m_values.assign(a.value_count, 0.0);
  m_local_row.assign(static_cast<std::size_t>(a.size()), 0);
  m_head.assign(static_cast<std::size_t>(a.supernodes()), -1);
  m_next.assign(m_head.size(), -1);
  m_position.assign(m_head.size(), 0);
  m_scaled.resize(a.scratch_size);
  m_update.resize(update_capacity);
  m_ok = false;
}

bool SupernodalLdlt::factorize(const Eigen::SparseMatrix<double>& lower)
{
  const SupernodalSymbolic& a = *m_symbolic;
  m_ok = false;
  std::vector<float>().swap(m_single);
  m_values.assign(a.value_count, 0.0);
  const double* values = lower.valuePtr();
  for (std::size_t p = 0; p < a.scatter.size(); ++p)
    m_values[static_cast<std::size_t>(a.scatter[p])] += values[p];
  m_pivots.resize(a.size());
  m_negative = 0;
  const bool ok = walk_supernodes(
      a, m_head, m_next, m_position,
      [&](int s) {
        for (int r = a.row_start[s]; r < a.row_start[s + 1]; ++r)
          m_local_row[static_cast<std::size_t>(a.rows[static_cast<std::size_t>(r)])] =
              r - a.row_start[s];
      },
      [&](int d, int first, int last, int s) { apply_descendant(d, first, last, s); },
      [&](int s) { return factorize_supernode(s); });
  if (!ok) {
    m_pivots.resize(0);
    return false;
  }
  m_ok = true;
  return true;
}

void SupernodalLdlt::apply_descendant(int d, int first, int last, int s)
{
  const SupernodalSymbolic& a = *m_symbolic;
  const int* rows = a.rows.data() + a.row_start[d];
  const int height = a.row_start[d + 1] - a.row_start[d];
  const int width = a.super[d + 1] - a.super[d];
  const double* L = m_values.data() + a.value_start[static_cast<std::size_t>(d)];
  const int inside = last - first; // rows of d that are columns of s
  const int below = height - first;

  // update = L_d(first:, :) D_d L_d(first:last, :)^T, below x inside, in blocks of rows.
  double* scaled = m_scaled.data();
  for (int c = 0; c < width; ++c) {
    const double pivot = L[c + static_cast<std::ptrdiff_t>(c) * height];
    const double* column = L + static_cast<std::ptrdiff_t>(c) * height + first;
    for (int r = 0; r < inside; ++r)
      scaled[r + static_cast<std::ptrdiff_t>(c) * inside] = column[r] * pivot;
  }
  double* target = m_values.data() + a.value_start[static_cast<std::size_t>(s)];
  const int target_height = a.row_start[s + 1] - a.row_start[s];
  const int first_column = a.super[s];
  const int block =
      std::max(1, static_cast<int>(update_capacity / static_cast<std::size_t>(inside)));
  double* update = m_update.data();
  for (int begin = 0; begin < below; begin += block) {
    const int count = std::min(block, below - begin);
    gemm_nt(count, inside, width, 1.0, L + first + begin, height, scaled, inside, 0.0, update,
            count);
    for (int j = 0; j < inside; ++j) {
      double* column =
          target + static_cast<std::ptrdiff_t>(rows[first + j] - first_column) * target_height;
      const double* from = update + static_cast<std::ptrdiff_t>(j) * count - begin;
      for (int i = std::max(j, begin); i < begin + count; ++i)
        column[m_local_row[static_cast<std::size_t>(rows[first + i])]] -= from[i];
    }
  }
}

bool SupernodalLdlt::factorize_supernode(int s)
{
  const SupernodalSymbolic& a = *m_symbolic;
  const int height = a.row_start[s + 1] - a.row_start[s];
  const int width = a.super[s + 1] - a.super[s];
  double* L = m_values.data() + a.value_start[static_cast<std::size_t>(s)];
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
      m_pivots(a.super[s] + j) = pivot;
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

namespace {

/// Forward substitution, pivots, back substitution with L's blocks `values` in precision Scalar.
template <class Scalar>
Eigen::VectorXd solve_with(const SupernodalSymbolic& a, const Scalar* values,
                           const Eigen::VectorXd& pivots, const Eigen::VectorXd& b)
{
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Block = Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>, 0,
                           Eigen::OuterStride<>>;
  const int n = a.size();
  Vector y(n);
  for (int k = 0; k < n; ++k)
    y(k) = static_cast<Scalar>(b(a.perm[static_cast<std::size_t>(k)]));
  Vector scratch(a.tallest);
  const int supernodes = a.supernodes();
  for (int s = 0; s < supernodes; ++s) {
    const int width = a.super[s + 1] - a.super[s];
    const int height = a.row_start[s + 1] - a.row_start[s];
    const Block L(values + a.value_start[static_cast<std::size_t>(s)], height, width,
                  Eigen::OuterStride<>(height));
    Eigen::Ref<Vector> x = y.segment(a.super[s], width);
    L.topRows(width).template triangularView<Eigen::UnitLower>().solveInPlace(x);
    const int below = height - width;
    if (below == 0)
      continue;
    scratch.head(below).noalias() = L.bottomRows(below) * x;
    const int* rows = a.rows.data() + a.row_start[s] + width;
    for (int r = 0; r < below; ++r)
      y(rows[r]) -= scratch(r);
  }
  y.array() /= pivots.array().template cast<Scalar>();
  for (int s = supernodes - 1; s >= 0; --s) {
    const int width = a.super[s + 1] - a.super[s];
    const int height = a.row_start[s + 1] - a.row_start[s];
    const Block L(values + a.value_start[static_cast<std::size_t>(s)], height, width,
                  Eigen::OuterStride<>(height));
    Eigen::Ref<Vector> x = y.segment(a.super[s], width);
    const int below = height - width;
    if (below > 0) {
      const int* rows = a.rows.data() + a.row_start[s] + width;
      for (int r = 0; r < below; ++r)
        scratch(r) = y(rows[r]);
      x.noalias() -= L.bottomRows(below).transpose() * scratch.head(below);
    }
    L.topRows(width).template triangularView<Eigen::UnitLower>().transpose().solveInPlace(x);
  }
  Eigen::VectorXd result(n);
  for (int k = 0; k < n; ++k)
    result(a.perm[static_cast<std::size_t>(k)]) = static_cast<double>(y(k));
  return result;
}

} // namespace

Eigen::VectorXd SupernodalLdlt::solve(const Eigen::VectorXd& b) const
{
  return single_precision() ? solve_with(*m_symbolic, m_single.data(), m_pivots, b)
                            : solve_with(*m_symbolic, m_values.data(), m_pivots, b);
}

void SupernodalLdlt::to_single_precision()
{
  if (!m_ok || single_precision())
    return;
  m_single.assign(m_values.begin(), m_values.end());
  std::vector<double>().swap(m_values);
}

} // namespace ligsim::sim
