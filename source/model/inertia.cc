#include <coshell/base/expressions.h>
#include <coshell/element/shell_element.h>
#include <coshell/model/inertia.h>
#include <coshell/model/internal_force.h>

#include <deal.II/base/function_parser.h>
#include <deal.II/base/utilities.h>

#include <memory>
#include <stdexcept>

namespace coshell::model
{
  using namespace dealii;

  namespace
  {
    /// Three muparser expressions of x, y, z.
    std::unique_ptr<FunctionParser<3>> vector_field(const std::string &text,
                                                    const std::string &where)
    {
      return base::parse_expressions<3>(text, 3, "x,y,z", false, "x, y, z",
                                        where);
    }

    /// The three entries of a cell vertex's DoFs from 'first' on, through
    /// the model's table of vertex DoFs: deal.II's vertex_dof_index()
    /// would be most of the cost of a cell's rates.
    Tensor<1, 3> vertex_slot(const ShellModel     &model,
                             const Vector<double> &values,
                             const CellIterator   &cell,
                             unsigned int          v,
                             unsigned int          first)
    {
      return vertex_block(values, model.vertex_dofs(cell->vertex_index(v)),
                          first);
    }

    void require_non_negative(double value, const std::string &name)
    {
      if (!(value >= 0))
        throw std::invalid_argument("Mass and damping/" + name + " = " +
                                    std::to_string(value) +
                                    " must not be negative");
    }
  } // namespace

  void InertiaParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mass and damping");
    prm.declare_entry("Mass matrix", "consistent",
                      Patterns::Selection("consistent|lumped"),
                      "Translational mass rho h A: consistent (linear "
                      "interpolation of the velocity) or lumped (a third per "
                      "vertex). Used in dynamics only (Material/Density "
                      "gives rho).");
    prm.declare_entry("Rotary inertia factor", "1", Patterns::Double(0),
                      "Factor on the nodal rotary inertia "
                      "rho h^3/12 * A/3 (lumped, the same about every axis). "
                      "Larger values raise the highest (drilling and "
                      "bending) frequencies' periods, allowing larger "
                      "explicit-like steps, at the cost of accuracy in "
                      "fast rotations; must be > 0. Unit: dimensionless.");
    prm.declare_entry("Rayleigh mass coefficient", "0", Patterns::Double(0),
                      "alpha of the damping C = alpha M + beta K. Unit: "
                      "1/time (1/s).");
    prm.declare_entry("Rayleigh stiffness coefficient", "0",
                      Patterns::Double(0),
                      "beta of the damping C = alpha M + beta K (K: the "
                      "linear stiffness of the current triangles, which "
                      "does not damp rigid motions). Unit: time (s).");
    prm.declare_entry("Normal drag", "0", Patterns::Double(0),
                      "Viscous drag of the surrounding medium against the "
                      "normal velocity: force per area per velocity. Unit: "
                      "force*time/length^3 (N s/m^3 in SI, N s/mm^3 in "
                      "mm-N-s scenes).");
    prm.declare_entry("Tangential drag", "0", Patterns::Double(0),
                      "Viscous drag against the in-plane velocity: force "
                      "per area per velocity. Unit: force*time/length^3 (N "
                      "s/m^3 in SI, N s/mm^3 in mm-N-s scenes).");
    prm.declare_entry("Initial velocity", "0; 0; 0", Patterns::Anything(),
                      "Velocity at the start of the scene, three muparser "
                      "expressions of the position x, y, z separated by "
                      "';'. Unit: length/time (mm/s in the IOL scenes).");
    prm.declare_entry("Initial angular velocity", "0; 0; 0",
                      Patterns::Anything(),
                      "Angular velocity of the nodal triads at the start, "
                      "three expressions of x, y, z. Unit: rad/s.");
    prm.leave_subsection();
  }

  void InertiaParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mass and damping");
    mass_matrix              = prm.get("Mass matrix") == "lumped"
                                   ? element::MassMatrix::lumped
                                   : element::MassMatrix::consistent;
    rotary_inertia_factor    = prm.get_double("Rotary inertia factor");
    rayleigh_alpha           = prm.get_double("Rayleigh mass coefficient");
    rayleigh_beta            = prm.get_double("Rayleigh stiffness coefficient");
    normal_drag              = prm.get_double("Normal drag");
    tangential_drag          = prm.get_double("Tangential drag");
    initial_velocity         = prm.get("Initial velocity");
    initial_angular_velocity = prm.get("Initial angular velocity");
    prm.leave_subsection();
    if (rotary_inertia_factor <= 0)
      throw std::invalid_argument("Mass and damping/Rotary inertia factor = " +
                                  std::to_string(rotary_inertia_factor) +
                                  " must be positive (the rotations need "
                                  "mass)");
    require_non_negative(rayleigh_alpha, "Rayleigh mass coefficient");
    require_non_negative(rayleigh_beta, "Rayleigh stiffness coefficient");
    vector_field(initial_velocity, "Mass and damping/Initial velocity");
    vector_field(initial_angular_velocity,
                 "Mass and damping/Initial angular velocity");
  }

  bool InertiaParameters::damped() const
  {
    return rayleigh_alpha > 0 || rayleigh_beta > 0 || normal_drag > 0 ||
           tangential_drag > 0;
  }

  Inertia::Inertia(const ShellModel        &model,
                   const InertiaParameters &parameters,
                   bool                     body_frame_translations)
      : model_(model), parameters_(parameters),
        body_frame_translations_(body_frame_translations)
  {
    // The mass of a cell is of its reference triangle and material, fixed
    // for the model's life (as the element stiffness InternalForce keeps):
    // made once, not at every cell of every evaluation.
    mass_entries_.resize(model.surface().n_active_cells());
    for (const auto &cell : model.dof_handler().active_cell_iterators())
      mass_entries_[cell->active_cell_index()] = element::shell_mass_entries(
          model.triangle(cell), mass_properties(cell));
  }

  const element::MassEntries &
  Inertia::mass_entries(const CellIterator &cell) const
  {
    return mass_entries_[cell->active_cell_index()];
  }

  element::MassProperties
  Inertia::mass_properties(const CellIterator &cell) const
  {
    const auto &material = model_.material(cell);
    return {material.density, material.thickness,
            parameters_.rotary_inertia_factor, parameters_.mass_matrix};
  }

  std::string Inertia::name() const
  {
    return "inertia and damping";
  }

  ForceKind Inertia::kind() const
  {
    return ForceKind::inertia;
  }

  bool Inertia::has_cell_terms() const
  {
    return true;
  }

  bool Inertia::symmetric_tangent() const
  {
    return !body_frame_translations_;
  }

  std::array<double, element::shell_dofs> Inertia::spatial_rates(
      const CellIterator &cell, const ShellState &state, Rate rate) const
  {
    const Vector<double> &rates =
        rate == Rate::velocity ? state.velocity() : state.acceleration();
    const auto slot =
        [&](const Vector<double> &values, unsigned int v, unsigned int first)
    { return vertex_slot(model_, values, cell, v, first); };
    std::array<double, element::shell_dofs> spatial;
    for (unsigned int v = 0; v < 3; ++v)
    {
      Tensor<1, 3> translation = slot(rates, v, ux);
      Tensor<1, 3> rotation    = slot(rates, v, rx);
      if (state.body_frame_translations())
      {
        // dx/dt = R v; d2x/dt2 = R (dv/dt + Omega x v).
        if (rate == Rate::acceleration)
          translation += cross_product_3d(slot(state.velocity(), v, rx),
                                          slot(state.velocity(), v, ux));
        translation = state.rotation(cell->vertex_index(v)) * translation;
      }
      if (state.finite_rotations())
        rotation = state.rotation(cell->vertex_index(v)) * rotation;
      for (unsigned int d = 0; d < 3; ++d)
      {
        spatial[6 * v + d]     = translation[d];
        spatial[6 * v + 3 + d] = rotation[d];
      }
    }
    return spatial;
  }

  void Inertia::times_rate_jacobian(const FullMatrix<double> &matrix,
                                    const CellIterator       &cell,
                                    const ShellState         &state,
                                    Rate                      rate,
                                    double                    coefficient,
                                    double                    gyroscopic,
                                    FullMatrix<double>       &result) const
  {
    result.reinit(matrix.m(), matrix.n());
    result.add(coefficient, matrix);
    if (!state.body_frame_translations())
      return;
    const auto slot =
        [&](const Vector<double> &values, unsigned int v, unsigned int first)
    { return vertex_slot(model_, values, cell, v, first); };
    for (unsigned int v = 0; v < 3; ++v)
    {
      const unsigned int  vertex = cell->vertex_index(v);
      const Tensor<2, 3> &R      = state.rotation(vertex);
      const Tensor<1, 3>  omega  = slot(state.velocity(), v, rx);
      const Tensor<1, 3>  body_v = slot(state.velocity(), v, ux);
      // The body rate w whose spatial form R w is differentiated.
      Tensor<1, 3> w = body_v;
      if (rate == Rate::acceleration)
        w = slot(state.acceleration(), v, ux) + cross_product_3d(omega, body_v);
      Tensor<2, 3> dw_dq = gyroscopic * element::skew(omega);
      for (unsigned int d = 0; d < 3; ++d)
        dw_dq[d][d] += coefficient;
      // Translation columns: through q_u = V(psi)^-1 R_n^T (x - x_n).
      const Tensor<2, 3> translation =
          R * dw_dq * state.step_translation_jacobian(vertex);
      // Rotation columns (spatial spin d_theta, material d_phi = R^T
      // d_theta): R itself turns, Omega moves with c_v d_phi, and q_u with
      // (1/2) skew(d) d_phi, d = R_n^T (x - x_n) (leading term of V^-1).
      const Tensor<2, 3> rotation =
          R *
          (-element::skew(w) - gyroscopic * element::skew(body_v) +
           0.5 * dw_dq * element::skew(state.body_step_translation(vertex))) *
          transpose(R);
      for (unsigned int i = 0; i < matrix.m(); ++i)
        for (unsigned int e = 0; e < 3; ++e)
        {
          double along_translation = 0, along_rotation = 0;
          for (unsigned int d = 0; d < 3; ++d)
          {
            along_translation += matrix(i, 6 * v + d) * translation[d][e];
            along_rotation += matrix(i, 6 * v + d) * rotation[d][e];
          }
          result(i, 6 * v + e) = along_translation;
          result(i, 6 * v + 3 + e) += along_rotation;
        }
    }
  }

  void Inertia::damping(const CellIterator             &cell,
                        const element::SpatialTriangle &current,
                        const FullMatrix<double>       &mass,
                        FullMatrix<double>             &c,
                        FullMatrix<double>             &drag) const
  {
    c.reinit(element::shell_dofs, element::shell_dofs);
    if (parameters_.rayleigh_alpha > 0)
      c.add(parameters_.rayleigh_alpha, mass);
    if (parameters_.rayleigh_beta > 0)
    {
      c.add(parameters_.rayleigh_beta,
            element::shell_stiffness(current, model_.material(cell),
                                     model_.element_options(cell)));
    }
    if (parameters_.normal_drag > 0 || parameters_.tangential_drag > 0)
    {
      element::drag_matrix(current, parameters_.normal_drag,
                           parameters_.tangential_drag, drag);
      for (unsigned int a = 0; a < 9; ++a)
        for (unsigned int b = 0; b < 9; ++b)
          c(6 * (a / 3) + a % 3, 6 * (b / 3) + b % 3) += drag(a, b);
    }
  }

  namespace
  {
    /// The matrices of one cell, kept per thread: add_cell() runs once per
    /// cell and evaluation, on several cells at once, and allocating them
    /// each time would show in every assembly.
    struct CellMatrices
    {
      FullMatrix<double> mass, damping, drag, product;
    };

    CellMatrices &cell_matrices()
    {
      thread_local CellMatrices matrices;
      return matrices;
    }
  } // namespace

  namespace
  {
    /// A cell matrix of the mass's structure by its entries that may be
    /// nonzero, row by row, columns ascending: the mass has 36 of its 324
    /// entries, the damping alpha M plus the drag at most 54. Its products
    /// take the same terms in the same order as the dense ones, less the
    /// zeros, so they give the same numbers; they run once per cell and
    /// evaluation, where the dense 18x18 products and their zeroing would
    /// be a sizeable part of a haptic step.
    class SparseCellMatrix
    {
    public:
      /// M: m_ab I between the translations of vertices a and b, the rotary
      /// inertia on each rotation.
      explicit SparseCellMatrix(const element::MassEntries &mass)
      {
        for (unsigned int a = 0; a < 3; ++a)
        {
          for (unsigned int d = 0; d < 3; ++d, end_row())
            for (unsigned int b = 0; b < 3; ++b)
              add(6 * b + d, mass.translational[a][b]);
          for (unsigned int d = 0; d < 3; ++d, end_row())
            add(6 * a + 3 + d, mass.rotary);
        }
      }
      /// C = alpha M + the drag's 9x9 translational block of each vertex
      /// ('drag' null: none), entry by entry as Inertia::damping() sums
      /// them: alpha m first, then the drag.
      SparseCellMatrix(double                            alpha,
                       const element::MassEntries       &mass,
                       const dealii::FullMatrix<double> *drag)
      {
        for (unsigned int a = 0; a < 3; ++a)
        {
          for (unsigned int d = 0; d < 3; ++d, end_row())
            for (unsigned int b = 0; b < 3; ++b)
              for (unsigned int e = 0; e < 3; ++e)
              {
                const bool mass_part = alpha > 0 && e == d,
                           drag_part = drag && b == a;
                if (!mass_part && !drag_part)
                  continue; // zero in C too
                double value = mass_part ? alpha * mass.translational[a][b] : 0;
                if (drag_part)
                  value += (*drag)(3 * a + d, 3 * a + e);
                add(6 * b + e, value);
              }
          for (unsigned int d = 0; d < 3; ++d, end_row())
            add(6 * a + 3 + d, alpha > 0 ? alpha * mass.rotary : 0);
        }
      }
      /// out_i -= sum_j A_ij r_j (or += with 'sign' = 1), term by term.
      template<typename Out>
      void add_times(double                                         sign,
                     const std::array<double, element::shell_dofs> &rates,
                     Out                                           &out) const
      {
        for (unsigned int i = 0, k = 0; i < element::shell_dofs; ++i)
          for (; k < row_end_[i]; ++k)
          {
            if (sign < 0)
              out[i] -= value_[k] * rates[column_[k]];
            else
              out[i] += value_[k] * rates[column_[k]];
          }
      }
      /// matrix += coefficient A.
      void add_to(double coefficient, dealii::FullMatrix<double> &matrix) const
      {
        for (unsigned int i = 0, k = 0; i < element::shell_dofs; ++i)
          for (; k < row_end_[i]; ++k)
            matrix(i, column_[k]) += coefficient * value_[k];
      }

    private:
      std::array<unsigned char, element::shell_dofs> row_end_{};
      std::array<unsigned char, 54>                  column_{};
      std::array<double, 54>                         value_{};
      unsigned int                                   size_ = 0, row_ = 0;

      void add(unsigned int column, double value)
      {
        Assert(size_ < value_.size(), dealii::ExcInternalError());
        column_[size_]  = column;
        value_[size_++] = value;
      }
      void end_row()
      {
        row_end_[row_++] = size_;
      }
    };

    using CellRates = std::array<double, element::shell_dofs>;

    /// Adds a cell's momenta and kinetic energy, from its vertices'
    /// positions, spatial velocities and momenta M v.
    void add_kinetic_measures(const element::SpatialTriangle &current,
                              const CellRates                &velocity,
                              const CellRates                &momentum,
                              KineticMeasures                &result)
    {
      for (unsigned int v = 0; v < 3; ++v)
      {
        Tensor<1, 3> p, spin_momentum;
        for (unsigned int d = 0; d < 3; ++d)
        {
          p[d]             = momentum[6 * v + d];
          spin_momentum[d] = momentum[6 * v + 3 + d];
        }
        result.linear_momentum += p;
        result.angular_momentum +=
            cross_product_3d(current[v], p) + spin_momentum;
      }
      for (unsigned int i = 0; i < element::shell_dofs; ++i)
        result.kinetic_energy += 0.5 * velocity[i] * momentum[i];
    }

    /// A cell's entries of a global vector, by kernel index. The indices
    /// are looked up once: a sparse cell matrix visits each row up to nine
    /// times, and deal.II's vertex_dof_index() would be a large part of
    /// the cost of Inertia::damping_force().
    class GlobalEntries
    {
    public:
      GlobalEntries(Vector<double>     &vector,
                    const ShellModel   &model,
                    const CellIterator &cell)
          : vector_(vector)
      {
        for (unsigned int i = 0; i < element::shell_dofs; ++i)
          dofs_[i] = model.vertex_dofs(cell->vertex_index(i / 6))[i % 6];
      }
      double &operator[](unsigned int i)
      {
        return vector_[dofs_[i]];
      }

    private:
      Vector<double>                                          &vector_;
      std::array<types::global_dof_index, element::shell_dofs> dofs_;
    };

    /// The damping and drag of a cell of the mass's structure (no
    /// stiffness-proportional damping), as Inertia::damping() makes it.
    SparseCellMatrix sparse_damping(const InertiaParameters        &parameters,
                                    const element::SpatialTriangle &current,
                                    const element::MassEntries     &mass,
                                    dealii::FullMatrix<double>     &drag)
    {
      const bool dragged =
          parameters.normal_drag > 0 || parameters.tangential_drag > 0;
      if (dragged)
        element::drag_matrix(current, parameters.normal_drag,
                             parameters.tangential_drag, drag);
      return SparseCellMatrix(parameters.rayleigh_alpha, mass,
                              dragged ? &drag : nullptr);
    }
  } // namespace

  bool Inertia::sparse_cell_matrices(const ShellState &state) const
  {
    // Body-frame translations turn the rates' Jacobian; stiffness-
    // proportional damping fills C.
    return !state.body_frame_translations() && parameters_.rayleigh_beta == 0;
  }

  void Inertia::add_sparse_cell(const CellIterator    &cell,
                                const EvaluationPoint &point,
                                CellContribution      &contribution,
                                bool                   with_tangent) const
  {
    const ShellState      &state   = point.state;
    const auto            &entries = mass_entries(cell);
    const SparseCellMatrix mass(entries);
    mass.add_times(-1, spatial_rates(cell, state, Rate::acceleration),
                   contribution.vector);
    if (with_tangent)
      mass.add_to(point.acceleration_coefficient, contribution.matrix);
    if (!parameters_.damped())
      return;
    const SparseCellMatrix c =
        sparse_damping(parameters_, current_triangle(model_, cell, state),
                       entries, cell_matrices().drag);
    c.add_times(-1, spatial_rates(cell, state, Rate::velocity),
                contribution.vector);
    if (with_tangent && !point.rate_mass)
      c.add_to(point.velocity_coefficient, contribution.matrix);
  }

  void Inertia::add_cell(const CellIterator    &cell,
                         const EvaluationPoint &point,
                         CellContribution      &contribution,
                         bool                   with_tangent) const
  {
    if (sparse_cell_matrices(point.state))
    {
      add_sparse_cell(cell, point, contribution, with_tangent);
      return;
    }
    const ShellState   &state    = point.state;
    CellMatrices       &matrices = cell_matrices();
    FullMatrix<double> &mass     = matrices.mass;
    element::shell_mass(model_.triangle(cell), mass_properties(cell), mass);
    const auto acceleration = spatial_rates(cell, state, Rate::acceleration);
    for (unsigned int i = 0; i < element::shell_dofs; ++i)
      for (unsigned int j = 0; j < element::shell_dofs; ++j)
        contribution.vector[i] -= mass(i, j) * acceleration[j];
    if (with_tangent)
      add_inertia_tangent(cell, point, mass, contribution.matrix);
    if (!parameters_.damped())
      return;
    FullMatrix<double> &c = matrices.damping;
    damping(cell, current_triangle(model_, cell, state), mass, c,
            matrices.drag);
    const auto velocity = spatial_rates(cell, state, Rate::velocity);
    for (unsigned int i = 0; i < element::shell_dofs; ++i)
      for (unsigned int j = 0; j < element::shell_dofs; ++j)
        contribution.vector[i] -= c(i, j) * velocity[j];
    if (with_tangent && !point.rate_mass)
    {
      times_rate_jacobian(c, cell, state, Rate::velocity,
                          point.velocity_coefficient, 0, matrices.product);
      contribution.matrix.add(1.0, matrices.product);
    }
  }

  void Inertia::add_inertia_tangent(const CellIterator       &cell,
                                    const EvaluationPoint    &point,
                                    const FullMatrix<double> &mass,
                                    FullMatrix<double>       &matrix) const
  {
    const ShellState &state = point.state;
    if (!state.body_frame_translations())
    {
      matrix.add(point.acceleration_coefficient, mass);
      return;
    }
    if (!point.rate_mass)
    {
      // d/dx of M R (dv/dt + Omega x v) through the step increment.
      FullMatrix<double> &product = cell_matrices().product;
      times_rate_jacobian(mass, cell, state, Rate::acceleration,
                          point.acceleration_coefficient,
                          point.velocity_coefficient, product);
      matrix.add(1.0, product);
      return;
    }
    // d(force)/d(body acceleration): M R on the translations.
    for (unsigned int v = 0; v < 3; ++v)
    {
      const Tensor<2, 3> &R = state.rotation(cell->vertex_index(v));
      for (unsigned int i = 0; i < element::shell_dofs; ++i)
      {
        for (unsigned int e = 0; e < 3; ++e)
          for (unsigned int d = 0; d < 3; ++d)
            matrix(i, 6 * v + e) += mass(i, 6 * v + d) * R[d][e];
        for (unsigned int d = 3; d < 6; ++d)
          matrix(i, 6 * v + d) += mass(i, 6 * v + d);
      }
    }
  }

  bool Inertia::has_potential() const
  {
    return !body_frame_translations_;
  }

  namespace
  {
    double dot(const std::array<double, element::shell_dofs> &a,
               const std::array<double, element::shell_dofs> &b)
    {
      double sum = 0;
      for (unsigned int i = 0; i < element::shell_dofs; ++i)
        sum += a[i] * b[i];
      return sum;
    }

    std::array<double, element::shell_dofs>
    times(const FullMatrix<double>                      &matrix,
          const std::array<double, element::shell_dofs> &x)
    {
      std::array<double, element::shell_dofs> product{};
      for (unsigned int i = 0; i < element::shell_dofs; ++i)
        for (unsigned int j = 0; j < element::shell_dofs; ++j)
          product[i] += matrix(i, j) * x[j];
      return product;
    }
  } // namespace

  Inertia::CellRates Inertia::mass_times(const CellIterator &cell,
                                         const ShellState   &state,
                                         const CellRates    &rates) const
  {
    CellRates product{};
    if (sparse_cell_matrices(state))
    {
      SparseCellMatrix(mass_entries(cell)).add_times(1, rates, product);
      return product;
    }
    FullMatrix<double> &mass = cell_matrices().mass;
    element::shell_mass(model_.triangle(cell), mass_properties(cell), mass);
    return times(mass, rates);
  }

  Inertia::CellRates Inertia::damping_times(const CellIterator &cell,
                                            const ShellState   &state,
                                            const CellRates    &rates) const
  {
    CellMatrices &matrices = cell_matrices();
    const auto    current  = current_triangle(model_, cell, state);
    CellRates     product{};
    if (sparse_cell_matrices(state))
    {
      sparse_damping(parameters_, current, mass_entries(cell), matrices.drag)
          .add_times(1, rates, product);
      return product;
    }
    element::shell_mass(model_.triangle(cell), mass_properties(cell),
                        matrices.mass);
    damping(cell, current, matrices.mass, matrices.damping, matrices.drag);
    return times(matrices.damping, rates);
  }

  double Inertia::cell_energy(const CellIterator    &cell,
                              const EvaluationPoint &point) const
  {
    const double c_a = point.acceleration_coefficient,
                 c_v = point.velocity_coefficient;
    if (!(c_a > 0))
      return 0;
    const ShellState &state = point.state;
    const auto acceleration = spatial_rates(cell, state, Rate::acceleration);
    double     energy =
        dot(acceleration, mass_times(cell, state, acceleration)) / (2 * c_a);
    if (parameters_.damped() && c_v > 0)
    {
      const auto velocity = spatial_rates(cell, state, Rate::velocity);
      energy += dot(velocity, damping_times(cell, state, velocity)) / (2 * c_v);
    }
    return energy;
  }

  KineticMeasures Inertia::measures(const ShellState &state) const
  {
    KineticMeasures result;
    for (const auto &cell : model_.dof_handler().active_cell_iterators())
    {
      const auto velocity = spatial_rates(cell, state, Rate::velocity);
      add_kinetic_measures(current_triangle(model_, cell, state), velocity,
                           mass_times(cell, state, velocity), result);
    }
    return result;
  }

  void Inertia::damping_force(const ShellState &state,
                              Vector<double>   &force) const
  {
    force = 0;
    if (!parameters_.damped())
      return;
    CellMatrices &matrices = cell_matrices();
    const bool    sparse   = sparse_cell_matrices(state);
    for (const auto &cell : model_.dof_handler().active_cell_iterators())
    {
      const auto velocity = spatial_rates(cell, state, Rate::velocity);
      const auto current  = current_triangle(model_, cell, state);
      if (sparse)
      {
        GlobalEntries global(force, model_, cell);
        sparse_damping(parameters_, current, mass_entries(cell), matrices.drag)
            .add_times(1, velocity, global);
        continue;
      }
      element::shell_mass(model_.triangle(cell), mass_properties(cell),
                          matrices.mass);
      FullMatrix<double> &c = matrices.damping;
      damping(cell, current, matrices.mass, c, matrices.drag);
      GlobalEntries global(force, model_, cell);
      for (unsigned int i = 0; i < element::shell_dofs; ++i)
      {
        double &entry = global[i];
        for (unsigned int j = 0; j < element::shell_dofs; ++j)
          entry += c(i, j) * velocity[j];
      }
    }
  }

  void Inertia::set_initial_velocity(ShellState &state) const
  {
    const auto velocity = vector_field(parameters_.initial_velocity, "");
    const auto spin = vector_field(parameters_.initial_angular_velocity, "");
    Vector<double> value(3);
    const auto    &vertices = model_.surface().get_vertices();
    for (unsigned int v = 0; v < vertices.size(); ++v)
      if (model_.vertex_is_used(v))
      {
        const VertexDofs  &dofs = model_.vertex_dofs(v);
        const Tensor<2, 3> R    = state.rotation(v);
        velocity->vector_value(vertices[v], value);
        // Body-frame translational velocity v = R^T dx/dt with SE(3).
        Tensor<1, 3> dx_dt({value[0], value[1], value[2]});
        if (state.body_frame_translations())
          dx_dt = transpose(R) * dx_dt;
        for (unsigned int d = 0; d < 3; ++d)
          state.velocity()[dofs[ux + d]] = dx_dt[d];
        spin->vector_value(vertices[v], value);
        // Material angular velocity Omega = R^T omega.
        const Tensor<1, 3> omega({value[0], value[1], value[2]});
        const Tensor<1, 3> material =
            state.finite_rotations() ? transpose(R) * omega : omega;
        for (unsigned int d = 0; d < 3; ++d)
          state.velocity()[dofs[rx + d]] = material[d];
      }
  }
} // namespace coshell::model
