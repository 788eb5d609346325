#pragma once

#include <deal.II/lac/sparse_matrix.h>

#include <memory>
#include <utility>
#include <vector>

namespace coshell::solvers
{
  /// std::allocator, except that a vector grown by resize() leaves its
  /// new numbers uninitialized instead of zeroing them. CompressedRows
  /// grows its arrays to the pattern's size before every copy and
  /// shrinks them to the nonzeros after; zeroing most of them again each
  /// time (the room kept for contact that stays zero) would be paid at
  /// every step of a haptic loop.
  template<typename T>
  struct UninitializedAllocator : std::allocator<T>
  {
    template<typename U>
    struct rebind
    {
      using other = UninitializedAllocator<U>;
    };
    UninitializedAllocator() = default;
    template<typename U>
    UninitializedAllocator(const UninitializedAllocator<U> &)
    {
    }
    template<typename U>
    void construct(U *)
    {
    }
    template<typename U, typename... Args>
    void construct(U *p, Args &&...args)
    {
      ::new (static_cast<void *>(p)) U(std::forward<Args>(args)...);
    }
  };

  /// A copy of a deal.II SparseMatrix in plain compressed-row arrays, the
  /// form SuiteSparse reads (as compressed columns of the transpose),
  /// without the off-diagonal entries that are exactly zero: the solvers
  /// analyse again when that pattern changes.
  /// Column indices ascend within each row: deal.II stores the diagonal
  /// first, UMFPACK rejects unsorted columns.
  struct CompressedRows
  {
    std::vector<int, UninitializedAllocator<int>>       starts, indices;
    std::vector<double, UninitializedAllocator<double>> values;

    /// Copies the whole matrix, or with 'lower_only' only the entries
    /// with column <= row: all that CHOLMOD reads of a symmetric one.
    void copy(const dealii::SparseMatrix<double> &matrix,
              bool                                lower_only = false);
    bool same_pattern(const CompressedRows &other) const;
    int  n_rows() const;
  };
} // namespace coshell::solvers
