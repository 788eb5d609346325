// Google Benchmark timings of the element kernels and of global assembly
// (not tests: speed is measured here, never asserted). Run
//   build/benchmarks/coshell_element_benchmarks --benchmark_format=json
// or through doc/scripts/performance_measurements.py, which records the
// machine and commit.

#include <coshell/element/corotational.h>
#include <coshell/element/shell_element.h>
#include <coshell/mesh/mesh.h>
#include <coshell/model/cell_loop.h>
#include <coshell/model/internal_force.h>
#include <coshell/model/shell_model.h>
#include <coshell/model/shell_state.h>

#include <deal.II/base/multithread_info.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <benchmark/benchmark.h>

using namespace coshell;

namespace
{
  element::ShellMaterial plate_material()
  {
    element::ShellMaterial material;
    material.youngs_modulus = 1.092e6;
    material.poisson_ratio  = 0.3;
    material.thickness      = 0.1;
    return material;
  }

  const element::SpatialTriangle triangle = {
      {dealii::Point<3>(0.1, 0.2, 0.3), dealii::Point<3>(1.2, -0.3, 0.7),
       dealii::Point<3>(0.4, 0.9, -0.2)}};

  /// arg: 0 CST+DKT, 1 CST+Przemieniecki, 2 ANDES+DKT.
  element::ShellElementOptions options_for(int64_t variant)
  {
    element::ShellElementOptions options;
    if (variant == 2)
      options.membrane = element::MembraneElement::andes;
    const int64_t bending = variant == 1 ? 1 : 0;
    options.bending       = bending == 0 ? element::BendingElement::dkt
                                         : element::BendingElement::przemieniecki;
    return options;
  }

  /// Linear flat-shell stiffness, 18x18 in global axes (arg: see
  /// options_for).
  void linear_shell_kernel(benchmark::State &state)
  {
    const auto options = options_for(state.range(0));
    for (auto _ : state)
      benchmark::DoNotOptimize(
          element::shell_stiffness(triangle, plate_material(), options));
  }
  BENCHMARK(linear_shell_kernel)->Arg(0)->Arg(1)->Arg(2);

  /// Co-rotational force with the consistent tangent, the paper tangent,
  /// or no tangent (arg 0, 1, 2), at a deformed state.
  void corotational_kernel(benchmark::State &state)
  {
    const element::CorotationalShell shell(triangle, plate_material(),
                                           options_for(0));
    element::SpatialTriangle         current = triangle;
    current[1][2] += 0.2;
    const element::NodalRotations rotations = {
        {element::rotation_exp(dealii::Tensor<1, 3>({0.3, 0.1, 0.0})),
         element::rotation_exp(dealii::Tensor<1, 3>({0.0, 0.4, 0.1})),
         element::rotation_exp(dealii::Tensor<1, 3>({0.2, 0.0, 0.3}))}};
    const auto                  type = state.range(0) == 1
                                           ? element::CorotationalTangent::paper
                                           : element::CorotationalTangent::consistent;
    element::ShellDisplacements force;
    dealii::FullMatrix<double>  tangent(18, 18);
    for (auto _ : state)
    {
      shell.internal_force(current, rotations, type, force,
                           state.range(0) == 2 ? nullptr : &tangent);
      benchmark::DoNotOptimize(force);
    }
  }
  BENCHMARK(corotational_kernel)->Arg(0)->Arg(1)->Arg(2);

  /// Linear assembly of the clamped plate, 64 x 64 `crossed` (16384
  /// triangles, CST+DKT), per element. Args: threads (1, 2) and scatter:
  /// 0 runs geometry extraction + element kernels in the same WorkStream
  /// loop (model::for_each_cell) as assembly and discards the matrices,
  /// 1 is the full ShellModel::assemble_stiffness (kernels +
  /// AffineConstraints::distribute_local_to_global), so the scatter costs
  /// the difference.
  void plate_assembly(benchmark::State &state)
  {
    dealii::MultithreadInfo::set_thread_limit(state.range(0));
    mesh::Surface surface;
    mesh::make_rectangle(surface, 10, 10, 64, 64,
                         mesh::TrianglePattern::crossed);
    model::ElementParameters parameters;
    parameters.material = plate_material();
    const model::ShellModel           model(surface, parameters,
                                            dealii::Tensor<1, 3>({0, 0, 1}));
    dealii::AffineConstraints<double> constraints;
    constraints.close();
    dealii::SparsityPattern pattern;
    model.make_sparsity(constraints, pattern);
    dealii::SparseMatrix<double> matrix(pattern);
    const auto kernel_only = [&model](const model::CellIterator &cell,
                                      model::CellContribution   &contribution)
    {
      contribution.matrix = element::shell_stiffness(
          model.triangle(cell), model.element_parameters().material,
          model.element_parameters().options);
    };
    const auto discard = [](const model::CellContribution &contribution)
    { benchmark::DoNotOptimize(contribution.matrix(0, 0)); };
    for (auto _ : state)
      if (state.range(1) == 1)
        model.assemble_stiffness(constraints, matrix);
      else
        model::for_each_cell(model.dof_handler(), kernel_only, discard);
    state.counters["us_per_element"] =
        benchmark::Counter(surface.n_active_cells(),
                           benchmark::Counter::kIsIterationInvariantRate |
                               benchmark::Counter::kInvert);
  }
  BENCHMARK(plate_assembly)
      ->ArgsProduct({{1, 2}, {0, 1}})
      ->ArgNames({"threads", "scatter"})
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
} // namespace

BENCHMARK_MAIN();
