// The shell's inertia and damping as the model assembles them
// (model::Inertia in a ShellProblem) on a flat 2 x 1 plate, against
// integrals over the rectangle done by hand: the mass matrix's total mass
// and rotary inertia, its symmetry and a lower bound on its eigenvalues,
// the kinetic energy and momenta of a rigid spin (exact with the
// consistent mass, which integrates products of linear fields exactly),
// Newton's second law for a uniform acceleration, and damping that
// spares rigid motions (stiffness-proportional) or matches its
// coefficients (mass-proportional, drag).

#include <coshell/mesh/mesh.h>
#include <coshell/model/inertia.h>
#include <coshell/model/shell_problem.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <sstream>
#include <string>

using namespace coshell;

namespace
{
  using dealii::Tensor;
  using dealii::Vector;

  constexpr double length_x = 2, length_y = 1, density = 3, thickness = 0.1,
                   rotary_factor = 2;
  constexpr double area          = length_x * length_y;

  /// rho h A and the whole rotary inertia factor rho h^3 / 12 A.
  double plate_mass()
  {
    return density * thickness * area;
  }
  double plate_rotary_inertia()
  {
    return rotary_factor * density * std::pow(thickness, 3) / 12 * area;
  }

  /// The plate [0, 2] x [0, 1] (z = 0) in 4 x 2 crossed squares, its
  /// state and a ShellProblem whose one contribution is the inertia.
  struct Plate
  {
    mesh::Surface surface;
    const bool    meshed =
        (mesh::make_rectangle(
             surface, length_x, length_y, 4, 2, mesh::TrianglePattern::crossed),
         true);
    const model::ShellModel              model;
    model::ShellState                    state{model, true};
    dealii::AffineConstraints<double>    constraints;
    std::unique_ptr<model::ShellProblem> problem;
    const model::Inertia                *inertia = nullptr;

    explicit Plate(const model::InertiaParameters &parameters)
        : model(surface, element_parameters(), Tensor<1, 3>({0, 0, 1}))
    {
      constraints.close();
      auto owned = std::make_unique<model::Inertia>(model, parameters);
      inertia    = owned.get();
      std::vector<std::unique_ptr<model::Contribution>> contributions;
      contributions.push_back(std::move(owned));
      problem = std::make_unique<model::ShellProblem>(model, state, constraints,
                                                      std::move(contributions));
    }

    static model::ElementParameters element_parameters()
    {
      model::ElementParameters parameters;
      parameters.material.youngs_modulus = 1000;
      parameters.material.poisson_ratio  = 0.3;
      parameters.material.thickness      = thickness;
      parameters.material.density        = density;
      return parameters;
    }

    /// The assembled (here unconstrained) mass matrix, dense.
    dealii::FullMatrix<double> mass_matrix()
    {
      base::TangentMatrix mass;
      problem->reinit_tangent(mass);
      problem->mass_matrix(mass);
      dealii::FullMatrix<double> full;
      full.copy_from(mass.serial());
      return full;
    }

    /// 'translation' on every translation slot and 'rotation' on every
    /// rotation slot (material = spatial here: no rotation yet).
    Vector<double> uniform(const Tensor<1, 3> &translation,
                           const Tensor<1, 3> &rotation) const
    {
      Vector<double> v(model.n_dofs());
      const auto    &vertices = surface.get_vertices();
      for (unsigned int i = 0; i < vertices.size(); ++i)
        if (model.vertex_is_used(i))
          for (unsigned int d = 0; d < 3; ++d)
          {
            v[model.vertex_dofs(i)[model::ux + d]] = translation[d];
            v[model.vertex_dofs(i)[model::rx + d]] = rotation[d];
          }
      return v;
    }

    /// The velocity of a rigid motion spinning at 'omega' about the axis
    /// through 'centre', translations and rotations.
    Vector<double> rigid_spin(const Tensor<1, 3>     &omega,
                              const dealii::Point<3> &centre) const
    {
      Vector<double> v        = uniform({}, omega);
      const auto    &vertices = surface.get_vertices();
      for (unsigned int i = 0; i < vertices.size(); ++i)
        if (model.vertex_is_used(i))
        {
          const Tensor<1, 3> velocity =
              dealii::cross_product_3d(omega, vertices[i] - centre);
          for (unsigned int d = 0; d < 3; ++d)
            v[model.vertex_dofs(i)[model::ux + d]] = velocity[d];
        }
      return v;
    }
  };

  Tensor<1, 3> unit(unsigned int d)
  {
    Tensor<1, 3> e;
    e[d] = 1;
    return e;
  }

  model::InertiaParameters inertia_parameters(element::MassMatrix type)
  {
    model::InertiaParameters parameters;
    parameters.mass_matrix           = type;
    parameters.rotary_inertia_factor = rotary_factor;
    return parameters;
  }

  /// Moments of the rectangle [0, Lx] x [0, Ly] in z = 0: A, int x dA and
  /// int x x^T dA.
  Tensor<1, 3> first_moment()
  {
    return Tensor<1, 3>({length_x * length_x * length_y / 2,
                         length_x * length_y * length_y / 2, 0});
  }
  Tensor<2, 3> second_moment()
  {
    Tensor<2, 3> m;
    m[0][0] = std::pow(length_x, 3) * length_y / 3;
    m[1][1] = length_x * std::pow(length_y, 3) / 3;
    m[0][1] = m[1][0] = std::pow(length_x * length_y, 2) / 4;
    return m;
  }

  double quadratic_form(const dealii::FullMatrix<double> &M,
                        const Vector<double>             &u,
                        const Vector<double>             &v)
  {
    return M.matrix_scalar_product(u, v);
  }
} // namespace

// u.M v for the unit rigid translations and unit uniform rotation rates:
// rho h A on each translation, the whole rotary inertia on each rotation,
// nothing between different directions or between translations and
// rotations; consistent and lumped alike.
TEST(Inertia, MassMatrixCarriesTheWholeMassAndRotaryInertia)
{
  for (const auto type :
       {element::MassMatrix::consistent, element::MassMatrix::lumped})
  {
    SCOPED_TRACE(type == element::MassMatrix::consistent ? "consistent"
                                                         : "lumped");
    Plate      plate(inertia_parameters(type));
    const auto M = plate.mass_matrix();
    for (unsigned int d = 0; d < 3; ++d)
      for (unsigned int e = 0; e < 3; ++e)
      {
        const auto ud = plate.uniform(unit(d), {}),
                   ue = plate.uniform(unit(e), {}),
                   rd = plate.uniform({}, unit(d)),
                   re = plate.uniform({}, unit(e));
        EXPECT_NEAR(quadratic_form(M, ud, ue), d == e ? plate_mass() : 0,
                    1e-13);
        EXPECT_NEAR(quadratic_form(M, rd, re),
                    d == e ? plate_rotary_inertia() : 0, 1e-17);
        EXPECT_EQ(quadratic_form(M, ud, re), 0);
      }
  }
}

// The consistent mass is symmetric to the bit and positive definite, its
// smallest eigenvalue at least the smallest of the element bounds: a
// triangle's translational block rho h A_e / 12 (I + 1 1^T) has
// eigenvalues rho h A_e / 12 x {4, 1, 1}, its rotary one J A_e / 3, and a
// sum of such blocks cannot go below their smallest eigenvalue.
TEST(Inertia, ConsistentMassIsSymmetricPositiveDefinite)
{
  Plate      plate(inertia_parameters(element::MassMatrix::consistent));
  const auto M = plate.mass_matrix();
  for (unsigned int i = 0; i < M.m(); ++i)
    for (unsigned int j = 0; j < i; ++j)
      ASSERT_EQ(M(i, j), M(j, i)) << i << ", " << j;
  // 8 squares of 0.5 x 0.5 in 4 triangles: A_e = 1/16.
  const double element_area = area / 32;
  const double bound        = std::min(
             density * thickness * element_area / 12,
             rotary_factor * density * std::pow(thickness, 3) / 12 * element_area / 3);
  dealii::LAPACKFullMatrix<double> lapack;
  lapack.copy_from(M);
  lapack.compute_eigenvalues();
  double smallest = 1e300;
  for (unsigned int k = 0; k < M.m(); ++k)
  {
    EXPECT_EQ(lapack.eigenvalue(k).imag(), 0);
    smallest = std::min(smallest, lapack.eigenvalue(k).real());
  }
  EXPECT_GE(smallest, bound * (1 - 1e-10));
}

// A rigid spin at omega about an axis through c, set from the expressions
// of Mass and damping/Initial velocity and Initial angular velocity:
// T = 1/2 rho h (|omega|^2 tr S - omega.S omega) + 1/2 J |omega|^2 with
// S = int (x - c)(x - c)^T dA; p = rho h omega x int (x - c) dA;
// L about 0 = rho h (tr Q omega - Q^T omega) + J omega with
// Q = int x (x - c)^T dA. The consistent mass gives all three exactly,
// the lumped one the linear momentum (vertex quadrature integrates linear
// fields).
TEST(Inertia, RigidSpinHasTheExactKineticEnergyAndMomenta)
{
  const Tensor<1, 3> omega({0.3, -0.2, 1.5});
  const Tensor<1, 3> c({0.5, 0.3, 0.2});
  const Tensor<1, 3> m1 = first_moment();
  Tensor<2, 3>       S  = second_moment() - dealii::outer_product(c, m1) -
                   dealii::outer_product(m1, c) +
                   area * dealii::outer_product(c, c);
  Tensor<2, 3> Q     = second_moment() - dealii::outer_product(m1, c);
  const double rho_h = density * thickness, J = plate_rotary_inertia();
  const double energy =
      0.5 * rho_h * (omega * omega * dealii::trace(S) - omega * (S * omega)) +
      0.5 * J * (omega * omega);
  const Tensor<1, 3> momentum =
      rho_h * dealii::cross_product_3d(omega, m1 - area * c);
  const Tensor<1, 3> angular =
      rho_h * (dealii::trace(Q) * omega - dealii::transpose(Q) * omega) +
      J * omega;

  // omega x (x - c), component by component, as muparser expressions.
  std::ostringstream velocity, spin;
  velocity.precision(17);
  spin.precision(17);
  const auto r = [&](unsigned int d)
  {
    std::ostringstream out;
    out.precision(17);
    out << "("
        << "xyz"[d] << " - (" << c[d] << "))";
    return out.str();
  };
  for (unsigned int d = 0; d < 3; ++d)
  {
    const unsigned int a = (d + 1) % 3, b = (d + 2) % 3;
    velocity << (d ? "; " : "") << "(" << omega[a] << ") * " << r(b) << " - ("
             << omega[b] << ") * " << r(a);
    spin << (d ? "; " : "") << omega[d];
  }

  for (const auto type :
       {element::MassMatrix::consistent, element::MassMatrix::lumped})
  {
    SCOPED_TRACE(type == element::MassMatrix::consistent ? "consistent"
                                                         : "lumped");
    model::InertiaParameters parameters = inertia_parameters(type);
    parameters.initial_velocity         = velocity.str();
    parameters.initial_angular_velocity = spin.str();
    Plate plate(parameters);
    plate.inertia->set_initial_velocity(plate.state);
    // The expressions gave the rigid field.
    Vector<double> difference = plate.rigid_spin(omega, dealii::Point<3>(c));
    difference -= plate.state.velocity();
    EXPECT_LT(difference.linfty_norm(), 1e-14);

    const model::KineticMeasures measures =
        plate.inertia->measures(plate.state);
    for (unsigned int d = 0; d < 3; ++d)
      EXPECT_NEAR(measures.linear_momentum[d], momentum[d], 1e-14) << d;
    if (type == element::MassMatrix::consistent)
    {
      EXPECT_NEAR(measures.kinetic_energy, energy, 1e-14 * energy);
      for (unsigned int d = 0; d < 3; ++d)
        EXPECT_NEAR(measures.angular_momentum[d], angular[d], 1e-14) << d;
    }
    else // vertex quadrature overestimates |x - c|^2: not exact
      EXPECT_GT(std::abs(measures.kinetic_energy - energy), 1e-6 * energy);
    // The energy is 1/2 v.M v with the assembled matrix.
    EXPECT_NEAR(
        measures.kinetic_energy,
        0.5 * plate.mass_matrix().matrix_norm_square(plate.state.velocity()),
        1e-14 * energy);
  }
}

// Newton's second law: under a uniform acceleration a0 and an angular one,
// the inertia force is -M acc, with resultant -rho h A a0; with rate
// coefficients (c_a, c_v) and no damping its tangent is c_a M.
TEST(Inertia, InertiaForceIsMinusMassTimesAcceleration)
{
  Plate              plate(inertia_parameters(element::MassMatrix::consistent));
  const Tensor<1, 3> a0({0.7, -1.1, 2.5}), alpha({0.2, 0.1, -0.4});
  plate.state.acceleration() = plate.uniform(a0, alpha);
  const auto M               = plate.mass_matrix();
  plate.problem->set_rate_coefficients(400, 20);
  base::TangentMatrix tangent;
  plate.problem->reinit_tangent(tangent);
  tangent.zero();
  Vector<double> residual(plate.model.n_dofs());
  plate.problem->evaluate(residual, &tangent);
  for (unsigned int d = 0; d < 3; ++d)
  {
    const Vector<double> along = plate.uniform(unit(d), {});
    EXPECT_NEAR(residual * along, -plate_mass() * a0[d], 1e-14) << d;
  }
  Vector<double> expected(residual.size());
  M.vmult(expected, plate.state.acceleration());
  expected *= -1;
  expected -= residual;
  EXPECT_LT(expected.linfty_norm(), 1e-15);
  dealii::FullMatrix<double> full;
  full.copy_from(tangent.serial());
  full.add(-400, M);
  EXPECT_LT(full.frobenius_norm(), 1e-12 * 400 * M.frobenius_norm());
}

// Damping of a moving plate: stiffness-proportional Rayleigh damping
// (beta K, K the linear stiffness) leaves a small rigid spin undamped,
// while it does damp a deformation rate of the same size;
// mass-proportional damping alpha M pulls a uniform velocity V back with
// alpha rho h A V; the medium's drag with c_n A V_n and c_t A V_t.
TEST(Inertia, DampingSparesRigidMotionsAndMatchesItsCoefficients)
{
  {
    model::InertiaParameters parameters =
        inertia_parameters(element::MassMatrix::consistent);
    parameters.rayleigh_beta = 0.01;
    Plate          plate(parameters);
    Vector<double> force(plate.model.n_dofs());
    plate.state.velocity() = plate.rigid_spin(Tensor<1, 3>({0.3, -0.2, 1.5}),
                                              dealii::Point<3>(0.5, 0.3, 0));
    plate.inertia->damping_force(plate.state, force);
    const double rigid = force.linfty_norm();
    // A deformation rate: the same field with the rotations left out.
    Vector<double> deforming = plate.state.velocity();
    for (unsigned int i = 0; i < plate.surface.n_vertices(); ++i)
      if (plate.model.vertex_is_used(i))
        for (unsigned int d = 0; d < 3; ++d)
          deforming[plate.model.vertex_dofs(i)[model::rx + d]] = 0;
    plate.state.velocity() = deforming;
    plate.inertia->damping_force(plate.state, force);
    EXPECT_GT(force.linfty_norm(), 1e-3);
    EXPECT_LT(rigid, 1e-12 * force.linfty_norm());
  }
  {
    model::InertiaParameters parameters =
        inertia_parameters(element::MassMatrix::lumped);
    parameters.rayleigh_alpha  = 0.5;
    parameters.normal_drag     = 7;
    parameters.tangential_drag = 2;
    Plate              plate(parameters);
    const Tensor<1, 3> V({0.4, -0.3, 1.2});
    plate.state.velocity() = plate.uniform(V, {});
    Vector<double> force(plate.model.n_dofs());
    plate.inertia->damping_force(plate.state, force);
    const double drag[3] = {2, 2, 7};
    for (unsigned int d = 0; d < 3; ++d)
    {
      const Vector<double> along = plate.uniform(unit(d), {});
      EXPECT_NEAR(force * along, (0.5 * plate_mass() + drag[d] * area) * V[d],
                  1e-13)
          << d;
    }
  }
}

// The inertia as backward Euler's incremental potential (Inertia::
// cell_energy through ShellProblem::energy()): with the rates of a step of
// size h from (v_n) set from the step increment q as the integrator sets
// them (v = q / h, a = (v - v_n) / h), the inertia and damping force is
// minus the gradient of a.M a / (2 c_a) + v.C v / (2 c_v), against central
// differences through the problem's own increment map. Mass-proportional
// damping (C = alpha M fixed) keeps it exact. With the step's rotations at
// zero (psi = 0) the rotations are exact as well, whatever the velocity
// the step starts from; with psi != 0 only the translations are checked:
// on rotations the gradient is the force to first order in psi
// (doc/theory/dynamics.md, "The incremental potential").
namespace
{
  struct SteppedPlate : Plate
  {
    const double   h = 0.01;
    Vector<double> v_n;

    explicit SteppedPlate(const model::InertiaParameters &parameters)
        : Plate(parameters), v_n(model.n_dofs())
    {
      for (unsigned int k = 0; k < v_n.size(); ++k)
        v_n[k] = 0.3 * std::sin(1.3 * k + 0.4);
      state.velocity() = v_n;
      problem->set_rate_coefficients(1 / (h * h), 1 / h);
      problem->save();
    }

    /// Backward Euler's rates of the present step increment.
    void update_rates()
    {
      Vector<double> q(model.n_dofs());
      problem->step_increment(q);
      state.velocity().equ(1 / h, q);
      state.acceleration() = state.velocity();
      state.acceleration() -= v_n;
      state.acceleration() /= h;
    }

    /// The energy after 'increment' from the step increment 'q0', which it
    /// goes back to.
    double energy_after(const Vector<double> &q0, const Vector<double> &inc)
    {
      problem->apply_increment(inc);
      update_rates();
      const double energy = problem->energy();
      problem->set_step_increment(q0);
      update_rates();
      return energy;
    }

    /// Largest |dE/dx_k + r_k| over the DoFs 'checked', relative to the
    /// largest |r_k|.
    double gradient_mismatch(const Vector<double>                    &q0,
                             const std::function<bool(unsigned int)> &checked)
    {
      problem->set_step_increment(q0);
      update_rates();
      Vector<double> residual(model.n_dofs());
      problem->evaluate(residual, nullptr);
      const double step     = 1e-7;
      double       mismatch = 0;
      for (unsigned int k = 0; k < residual.size(); ++k)
        if (checked(k))
        {
          Vector<double> inc(residual.size());
          inc[k]             = step;
          const double plus  = energy_after(q0, inc);
          inc[k]             = -step;
          const double minus = energy_after(q0, inc);
          mismatch           = std::max(
                        mismatch, std::abs((plus - minus) / (2 * step) + residual[k]));
        }
      return mismatch / residual.linfty_norm();
    }

    bool is_rotation(unsigned int k) const
    {
      for (unsigned int v = 0; v < surface.n_vertices(); ++v)
        for (unsigned int d = 0; d < 3; ++d)
          if (model.vertex_dofs(v)[model::rx + d] == k)
            return true;
      return false;
    }
  };
} // namespace

TEST(Inertia, IncrementalPotentialGradientIsTheInertiaForce)
{
  for (const auto type :
       {element::MassMatrix::consistent, element::MassMatrix::lumped})
  {
    model::InertiaParameters parameters = inertia_parameters(type);
    parameters.rayleigh_alpha           = 3;
    SteppedPlate   plate(parameters);
    Vector<double> q0(plate.model.n_dofs());
    for (unsigned int k = 0; k < q0.size(); ++k)
      if (!plate.is_rotation(k))
        q0[k] = 0.002 * std::cos(0.7 * k);
    EXPECT_LT(plate.gradient_mismatch(q0, [](unsigned int) { return true; }),
              1e-6);
    for (unsigned int k = 0; k < q0.size(); ++k)
      if (plate.is_rotation(k))
        q0[k] = 0.05 * std::sin(0.9 * k);
    EXPECT_LT(plate.gradient_mismatch(q0, [&plate](unsigned int k)
                                      { return !plate.is_rotation(k); }),
              1e-6);
  }
}

// With body-frame translations (SE3) the inertia force has no potential
// in these unknowns, and the problem says so (no energy to search on).
TEST(Inertia, BodyFrameTranslationsHaveNoPotential)
{
  const auto  parameters = inertia_parameters(element::MassMatrix::lumped);
  const Plate plate(parameters);
  const model::Inertia se3(plate.model, parameters, true);
  EXPECT_FALSE(se3.has_potential());
  EXPECT_TRUE(plate.inertia->has_potential());
}
