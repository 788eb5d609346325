// Benchmark (not a test): what each MPI rank holds for the mesh, the DoF
// handler, the sparsity pattern and one DoF vector of a unit square plate
// (crossed pattern, S x S squares, six DoFs per vertex; no constraints, no
// matrix values), in three layouts:
//   replicated        CoShell's nonlinear and dynamic analyses under mpirun:
//                     every rank holds the whole mesh (partitioned by METIS,
//                     the design of parallel::shared::Triangulation), the
//                     whole sparsity pattern and full-length vectors;
//   replicated-mesh   CoShell's linear statics: the whole mesh, but a
//                     Trilinos pattern of this rank's rows only;
//   fullydistributed  a parallel::fullydistributed::Triangulation built from
//                     a METIS-partitioned description (rank 0 builds the
//                     serial mesh once), a Trilinos pattern of owned rows
//                     and deal.II vectors of locally relevant DoFs; with
//                     --trilinos-vector also a ghosted Trilinos vector.
// Run one layout per process, so that the peak resident set is its own:
//   mpirun -np 2 build/benchmarks/coshell_mesh_memory fullydistributed 288
// Prints one JSON line (rank 0): the largest value over the ranks of each
// quantity, in bytes and seconds (totals are summed on each rank first).
// doc/scripts/mesh_memory.py runs the study.

#include <coshell/mesh/mesh.h>
#include <coshell/model/subdomain_dofs.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>
#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <malloc.h>

#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

using namespace dealii;

namespace
{
  constexpr unsigned int dofs_per_vertex = 6;
  const MPI_Comm         world           = MPI_COMM_WORLD;

  /// Resident memory of this process in bytes: now (VmRSS) and the peak
  /// so far (VmHWM).
  Utilities::System::MemoryStats memory_stats()
  {
    Utilities::System::MemoryStats stats;
    Utilities::System::get_memory_stats(stats);
    return stats;
  }

  double resident_now()
  {
    return 1024.0 * memory_stats().VmRSS;
  }

  double resident_peak()
  {
    return 1024.0 * memory_stats().VmHWM;
  }

  /// Per-rank quantities, reduced to their maximum over the ranks.
  using Report = std::map<std::string, double>;

  /// Bytes of heap in use (glibc's allocator: small blocks plus mmapped
  /// ones). Its growth between two marks is what a phase keeps allocated,
  /// which memory_consumption() does not report for Trilinos objects.
  class HeapMeter
  {
  public:
    explicit HeapMeter(Report &report) : report_(report), last_(in_use()) {}

    /// Records the growth since the previous mark as "heap_<name>_bytes"
    /// (and adds it to "kept_bytes"), and the process's peak so far as
    /// "peak_after_<name>_bytes": which phase sets the peak.
    void mark(const std::string &name)
    {
      const double now                   = in_use();
      report_["heap_" + name + "_bytes"] = now - last_;
      report_["kept_bytes"] += now - last_;
      report_["peak_after_" + name + "_bytes"] = resident_peak();
      last_                                    = now;
    }

    static double in_use()
    {
      const struct mallinfo2 info = mallinfo2();
      return double(info.uordblks) + double(info.hblkhd);
    }

  private:
    Report &report_;
    double  last_;
  };

  void make_plate(Triangulation<2, 3> &surface, unsigned int subdivisions)
  {
    coshell::mesh::make_rectangle(surface, 1.0, 1.0, subdivisions, subdivisions,
                                  coshell::mesh::TrianglePattern::crossed);
  }

  /// METIS, one part per rank, as coshell does under mpirun.
  void partition_for_ranks(Triangulation<2, 3> &surface, unsigned int n_ranks)
  {
    if (n_ranks > 1)
      coshell::mesh::partition(surface, n_ranks);
  }

  /// Counts and deal.II's own estimates, next to the heap marks.
  template<typename Pattern>
  void record_sizes(Report                    &report,
                    const Triangulation<2, 3> &surface,
                    const DoFHandler<2, 3>    &dofs,
                    const Pattern             &pattern)
  {
    report["n_dofs"]            = dofs.n_dofs();
    report["cells_stored"]      = surface.n_active_cells();
    report["mesh_bytes"]        = surface.memory_consumption();
    report["dof_handler_bytes"] = dofs.memory_consumption();
    report["sparsity_entries"]  = pattern.n_nonzero_elements();
  }

  /// Every rank builds and partitions the whole mesh and numbers all DoFs;
  /// with 'whole_pattern' it also holds the whole sparsity pattern (the
  /// nonlinear path), else a Trilinos pattern of its own rows (linear
  /// statics). Both keep full-length DoF vectors.
  void
  run_replicated(Report &report, unsigned int subdivisions, bool whole_pattern)
  {
    const unsigned int  n_ranks = Utilities::MPI::n_mpi_processes(world);
    const unsigned int  rank    = Utilities::MPI::this_mpi_process(world);
    HeapMeter           heap(report);
    Timer               timer;
    Triangulation<2, 3> surface;
    make_plate(surface, subdivisions);
    partition_for_ranks(surface, n_ranks);
    report["mesh_s"] = timer.wall_time();
    heap.mark("mesh");
    const FESystem<2, 3> fe(FE_SimplexP<2, 3>(1), dofs_per_vertex);
    DoFHandler<2, 3>     dofs(surface);
    dofs.distribute_dofs(fe);
    DoFRenumbering::subdomain_wise(dofs);
    heap.mark("dofs");
    SparsityPattern                   whole;
    TrilinosWrappers::SparsityPattern mine;
    if (whole_pattern)
    {
      DynamicSparsityPattern dynamic(dofs.n_dofs());
      DoFTools::make_sparsity_pattern(dofs, dynamic);
      whole.copy_from(dynamic);
    }
    else
    {
      const auto owned = DoFTools::locally_owned_dofs_per_subdomain(dofs)[rank];
      mine.reinit(owned, owned,
                  coshell::model::dofs_of_subdomain_cells(dofs, rank), world);
      DoFTools::make_sparsity_pattern(dofs, mine, AffineConstraints<double>(),
                                      false, rank);
      mine.compress();
    }
    report["setup_s"] = timer.wall_time();
    heap.mark("pattern");
    const Vector<double> vector(dofs.n_dofs());
    heap.mark("vector");
    if (whole_pattern)
      record_sizes(report, surface, dofs, whole);
    else
      record_sizes(report, surface, dofs, mine);
  }

  /// Rank 0 builds and partitions the serial mesh and sends each rank the
  /// description of its triangles and their ghost layer; every rank then
  /// numbers, couples and stores only its locally relevant DoFs.
  void run_fully_distributed(Report      &report,
                             unsigned int subdivisions,
                             bool         with_trilinos_vector)
  {
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(world);
    const unsigned int rank    = Utilities::MPI::this_mpi_process(world);
    HeapMeter          heap(report);
    Timer              timer;
    parallel::fullydistributed::Triangulation<2, 3> surface(world);
    {
      const auto description = TriangulationDescription::Utilities::
          create_description_from_triangulation_in_groups<2, 3>(
              [subdivisions](Triangulation<2, 3> &serial)
              { make_plate(serial, subdivisions); },
              [](Triangulation<2, 3> &serial, const MPI_Comm &comm,
                 unsigned int) {
                partition_for_ranks(serial,
                                    Utilities::MPI::n_mpi_processes(comm));
              },
              world, n_ranks);
      surface.create_triangulation(description);
    }
    report["mesh_s"] = timer.wall_time();
    heap.mark("mesh");
    const FESystem<2, 3> fe(FE_SimplexP<2, 3>(1), dofs_per_vertex);
    DoFHandler<2, 3>     dofs(surface);
    dofs.distribute_dofs(fe);
    const IndexSet &owned    = dofs.locally_owned_dofs();
    const IndexSet  relevant = DoFTools::extract_locally_relevant_dofs(dofs);
    heap.mark("dofs");
    TrilinosWrappers::SparsityPattern pattern(owned, owned, relevant, world);
    DoFTools::make_sparsity_pattern(dofs, pattern, AffineConstraints<double>(),
                                    false, rank);
    pattern.compress();
    report["setup_s"] = timer.wall_time();
    heap.mark("pattern");
    // deal.II's distributed vector would hold the rotation state on the
    // locally relevant DoFs; the solver's ghosted Trilinos vector only on
    // request, in its own run, since it raises the peak.
    const LinearAlgebra::distributed::Vector<double> vector(owned, relevant,
                                                            world);
    heap.mark("vector");
    TrilinosWrappers::MPI::Vector trilinos_vector;
    if (with_trilinos_vector)
    {
      trilinos_vector.reinit(owned, relevant, world);
      heap.mark("trilinos_vector");
    }
    record_sizes(report, surface, dofs, pattern);
    report["cells_owned"] = surface.n_locally_owned_active_cells();
  }

  void print_report(Report             report,
                    const std::string &layout,
                    unsigned int       subdivisions)
  {
    report["rss_bytes"]  = resident_now();
    report["peak_bytes"] = resident_peak();
    // Per rank, before the maxima: both terms from the same rank.
    report["peak_above_libraries_bytes"] =
        report["peak_bytes"] - report["rss_start_bytes"];
    std::ostringstream json;
    json << "{\"layout\": \"" << layout
         << "\", \"subdivisions\": " << subdivisions
         << ", \"ranks\": " << Utilities::MPI::n_mpi_processes(world);
    for (const auto &[key, value] : report)
    {
      const double largest = Utilities::MPI::max(value, world);
      json << ", \"" << key << "\": " << std::setprecision(12) << largest;
    }
    json << "}";
    if (Utilities::MPI::this_mpi_process(world) == 0)
      std::cout << json.str() << std::endl;
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const std::string                layout = argc >= 3 ? argv[1] : "";
  const bool                       with_trilinos_vector =
      argc == 4 && std::string(argv[3]) == "--trilinos-vector";
  if ((layout != "replicated" && layout != "replicated-mesh" &&
       layout != "fullydistributed") ||
      (argc == 4 && !(with_trilinos_vector && layout == "fullydistributed")))
  {
    std::cerr << "usage: coshell_mesh_memory "
                 "replicated|replicated-mesh|fullydistributed SUBDIVISIONS "
                 "[--trilinos-vector (fullydistributed)]\n";
    return 2;
  }
  const unsigned int subdivisions = std::stoul(argv[2]);
  Report             report;
  // The libraries alone (deal.II, Trilinos, MPI) are resident before any
  // mesh exists; the peak minus this is what the layout costs.
  report["rss_start_bytes"] = resident_now();
  if (layout == "fullydistributed")
    run_fully_distributed(report, subdivisions, with_trilinos_vector);
  else
    run_replicated(report, subdivisions, layout == "replicated");
  print_report(report,
               layout + (with_trilinos_vector ? "+trilinos-vector" : ""),
               subdivisions);
  return 0;
}
