#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace coshell::base
{
  /// The matrix a NonlinearProblem assembles its tangent into. On one rank
  /// it is a complete deal.II matrix. Under mpirun it is a Trilinos matrix
  /// of which each rank holds its own rows, assembled by the ranks
  /// together, so that no rank holds the whole tangent. The linear solver
  /// takes a distributed matrix over (it keeps reading it while its factors
  /// live); the next zero() builds a fresh one on the same pattern.
  class TangentMatrix
  {
  public:
    /// One rank: a matrix on 'pattern', which must outlive this.
    void reinit(const dealii::SparsityPattern &pattern);
    /// The same, where 'version' names the pattern's present contents
    /// (unique in the process, new whenever the pattern is made again):
    /// a matrix already on that pattern at that version keeps its storage
    /// and its values, which the next zero() clears. A Newton keeps its
    /// tangent so from one solve to the next: made anew each time step,
    /// the matrix would be allocated, zeroed and freed on top of the
    /// assembly's own zeroing.
    void reinit(const dealii::SparsityPattern &pattern, std::uint64_t version);
    /// Several ranks: this rank's rows of a matrix on 'pattern' (compressed,
    /// with the rows the rank writes to), which must outlive this.
    void reinit(const dealii::TrilinosWrappers::SparsityPattern &pattern);

    bool distributed() const;
    /// Sets every entry to zero, ready for assembly (builds the distributed
    /// matrix again once the solver has taken it).
    void zero();

    dealii::SparseMatrix<double> &serial();
    /// One rank only; reinit() unsets it. With 'lower' set, assembly may
    /// write only the entries with column <= row: all that CHOLMOD reads
    /// of a symmetric matrix (the upper triangle in its column storage).
    /// The others stay zero until mirror_lower().
    void set_lower_only(bool lower);
    bool lower_only() const;
    /// Copies each entry below the diagonal onto its mirror above it, for
    /// a reader of the whole matrix (UMFPACK, when CHOLMOD refuses it).
    /// The pattern must be symmetric.
    void mirror_lower();
    /// Only while distributed(), after zero().
    dealii::TrilinosWrappers::SparseMatrix &trilinos();
    /// Hands the assembled distributed matrix over; trilinos() is empty
    /// until the next zero().
    dealii::TrilinosWrappers::SparseMatrix take_trilinos();

  private:
    /// Set while distributed: a taken matrix is rebuilt on it.
    const dealii::TrilinosWrappers::SparsityPattern *trilinos_pattern_ =
        nullptr;
    dealii::SparseMatrix<double> serial_;
    /// The pattern and version serial_ was last made on by the versioned
    /// reinit() (null: none, or the unversioned one).
    const dealii::SparsityPattern *versioned_pattern_ = nullptr;
    std::uint64_t                  pattern_version_   = 0;
    bool                           lower_only_        = false;
    /// Value-array positions of each entry below the diagonal and of its
    /// mirror, found at the first mirror_lower() after reinit() (once per
    /// Newton solve that falls back to UMFPACK).
    std::vector<std::pair<std::size_t, std::size_t>> mirrors_;
    void                                             find_mirrors();
    /// Made only on the distributed path: a Trilinos object built before
    /// MPI starts (a serial run) would abort.
    std::unique_ptr<dealii::TrilinosWrappers::SparseMatrix> trilinos_;
  };

  /// A matrix view that passes on the rows of 'rows' and drops the others.
  /// Terms that every rank computes alike (contact pairs, found on the
  /// replicated configuration) go through it into a distributed matrix, so
  /// that each reaches the matrix once, from the rank that owns its row.
  /// It has what AffineConstraints::distribute_local_to_global() asks of a
  /// matrix.
  class RowsOf
  {
  public:
    using size_type  = dealii::types::global_dof_index;
    using value_type = double;

    RowsOf(dealii::TrilinosWrappers::SparseMatrix &matrix,
           const dealii::IndexSet                 &rows);
    /// Polymorphic because distribute_local_to_global() asks, by a
    /// dynamic_cast, whether a matrix is deal.II's own.
    virtual ~RowsOf() = default;

    size_type m() const;
    size_type n() const;
    /// One block (not a block matrix).
    unsigned int n_block_rows() const;
    unsigned int n_block_cols() const;

    void add(size_type        row,
             size_type        n_columns,
             const size_type *columns,
             const double    *values,
             bool             elide_zero_values  = true,
             bool             columns_are_sorted = false);
    void add(size_type row, size_type column, double value);

  private:
    dealii::TrilinosWrappers::SparseMatrix &matrix_;
    const dealii::IndexSet                 &rows_;
  };
} // namespace coshell::base
