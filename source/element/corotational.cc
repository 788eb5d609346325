// Co-rotational shell triangle (EICR, Rankin & Nour-Omid 1988; Felippa &
// Haugen 2005). The kinematic map p -> d (perturbation of the current state
// -> deformational DOFs) is differentiated in closed form; the material
// part stays the linear 1/2 d^T K_l d, contracted in double.
//
// The co-rotated frame E and the in-plane deformational translations
// depend on the 9 vertex translations u only, through the two edges.
// Writing a perturbed frame as E(u) = exp(skew(omega(u))) E, the
// deformational rotation of node i,
//   theta_d,i = axial log(E(u)^T exp(skew(theta_i)) R_i E0),
// depends on u only through the spin omega(u), so it is differentiated with
// respect to the 6 variables (omega, theta_i) and chained with the
// derivatives of omega(u). The translations and the frame's in-plane angle
// are invariant to rotations and differentiated (forward AD, Sacado) in the
// three scalars a.a, b.b, a.b of the edges a, b; the spin's normal part in
// closed form (doc/theory/corotational.md, section 13.4).

#include <coshell/element/corotational.h>

#include <deal.II/lac/vector.h>

#include <Sacado.hpp>

#include <cmath>
#include <optional>
#include <type_traits>

namespace coshell::element
{
  namespace
  {
    template<typename T>
    using Vec3 = std::array<T, 3>;
    /// Row-major 3x3 matrix.
    template<typename T>
    using Mat3 = std::array<Vec3<T>, 3>;
    /// The AD type of a mixed double/AD operation.
    template<typename A, typename B>
    using Product = std::conditional_t<std::is_same_v<A, double>, B, A>;

    template<typename T>
    double value_of(const T &x)
    {
      return Sacado::ScalarValue<T>::eval(x);
    }

    // ---- small vector algebra for double and AD scalars --------------------

    template<typename A, typename B>
    Product<A, B> dot(const Vec3<A> &a, const Vec3<B> &b)
    {
      return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    }

    template<typename T>
    Vec3<T> cross(const Vec3<T> &a, const Vec3<T> &b)
    {
      return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
               a[0] * b[1] - a[1] * b[0]}};
    }

    template<typename T>
    Vec3<T> operator-(const Vec3<T> &a, const Vec3<T> &b)
    {
      return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}};
    }

    template<typename T, typename S>
    Vec3<T> scaled(const S &factor, const Vec3<T> &a)
    {
      return {{factor * a[0], factor * a[1], factor * a[2]}};
    }

    template<typename T>
    Vec3<T> normalized(const Vec3<T> &a)
    {
      using std::sqrt;
      const T inverse_length = 1.0 / sqrt(dot(a, a));
      return scaled(inverse_length, a);
    }

    template<typename A, typename B>
    Mat3<Product<A, B>> product(const Mat3<A> &a, const Mat3<B> &b)
    {
      Mat3<Product<A, B>> c;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          c[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
      return c;
    }

    Mat3<double> to_mat3(const Tensor<2, 3> &t)
    {
      Mat3<double> m;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          m[i][j] = t[i][j];
      return m;
    }

    // ---- rotation maps -----------------------------------------------------

    // Below this squared argument the smooth functions of the rotation maps
    // are evaluated by their Taylor series: the closed forms are singular
    // at 0 (AD differentiates them) and lose digits in their derivatives.
    constexpr double series_limit = 1e-2;

    template<typename T, std::size_t n>
    T power_series(const T &y, const std::array<double, n> &coefficients)
    {
      T sum = coefficients[n - 1];
      for (std::size_t k = n - 1; k-- > 0;)
        sum = sum * y + coefficients[k];
      return sum;
    }

    // exp(skew(theta)) = I + sin(t)/t W + (1 - cos t)/t^2 W^2, W = skew(theta),
    // W^2 = theta theta^T - t^2 I.
    template<typename T>
    Mat3<T> exp_map(const Vec3<T> &theta)
    {
      using std::sin;
      using std::sqrt;
      const T angle_squared = dot(theta, theta);
      T       sin_ratio, cos_ratio; // sin(t)/t, (1 - cos t)/t^2
      if (value_of(angle_squared) < series_limit)
      {
        // Coefficients (-1)^k / (2k+1)! and (-1)^k / (2k+2)!.
        sin_ratio = power_series(
            angle_squared, std::array<double, 5>{{1.0, -1.0 / 6, 1.0 / 120,
                                                  -1.0 / 5040, 1.0 / 362880}});
        cos_ratio =
            power_series(angle_squared,
                         std::array<double, 5>{{0.5, -1.0 / 24, 1.0 / 720,
                                                -1.0 / 40320, 1.0 / 3628800}});
      }
      else
      {
        const T angle      = sqrt(angle_squared);
        const T half_ratio = sin(0.5 * angle) / angle;
        sin_ratio          = sin(angle) / angle;
        cos_ratio          = 2.0 * half_ratio * half_ratio; // no cancellation
      }
      Mat3<T> rotation;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          rotation[i][j] = cos_ratio * theta[i] * theta[j];
      for (unsigned int i = 0; i < 3; ++i)
      {
        const unsigned int j = (i + 1) % 3, k = (i + 2) % 3;
        rotation[i][i] += 1.0 - cos_ratio * angle_squared;
        rotation[k][j] += sin_ratio * theta[i];
        rotation[j][k] -= sin_ratio * theta[i];
      }
      return rotation;
    }

    // Unit quaternion (w, x, y, z) of a rotation by Shepperd's method: the
    // square root is taken of the largest of 4w^2, 4x^2, 4y^2, 4z^2 (which
    // is >= 1), and the sign makes w >= 0, i.e. the angle lies in [0, pi].
    template<typename T>
    std::array<T, 4> unit_quaternion(const Mat3<T> &r)
    {
      using std::sqrt;
      const T trace = r[0][0] + r[1][1] + r[2][2];
      int     pivot = -1; // -1: w, else the vector component
      double  best  = value_of(trace);
      for (int i = 0; i < 3; ++i)
        if (value_of(r[i][i]) > best)
        {
          pivot = i;
          best  = value_of(r[i][i]);
        }

      std::array<T, 4> q;
      if (pivot < 0)
      {
        q[0]            = 0.5 * sqrt(1.0 + trace);
        const T quarter = 0.25 / q[0];
        for (unsigned int i = 0; i < 3; ++i)
        {
          const unsigned int j = (i + 1) % 3, k = (i + 2) % 3;
          q[1 + i] = (r[k][j] - r[j][k]) * quarter;
        }
        return q;
      }
      const int i = pivot, j = (i + 1) % 3, k = (i + 2) % 3;
      q[1 + i]        = 0.5 * sqrt(1.0 + 2.0 * r[i][i] - trace);
      const T quarter = 0.25 / q[1 + i];
      q[0]            = (r[k][j] - r[j][k]) * quarter;
      q[1 + j]        = (r[j][i] + r[i][j]) * quarter;
      q[1 + k]        = (r[k][i] + r[i][k]) * quarter;
      if (value_of(q[0]) < 0.0)
        for (T &component : q)
          component = -component;
      return q;
    }

    // theta = 2 atan2(s, w) / s v for the quaternion (w, v), s = |v|.
    template<typename T>
    Vec3<T> log_map(const Mat3<T> &rotation)
    {
      using std::atan2;
      using std::sqrt;
      const std::array<T, 4> q         = unit_quaternion(rotation);
      const Vec3<T>          v         = {{q[1], q[2], q[3]}};
      const T                s_squared = dot(v, v);
      T                      factor;
      if (value_of(s_squared) < series_limit * value_of(q[0]) * value_of(q[0]))
      {
        // 2/w atan(x)/x with x^2 = s^2 / w^2; coefficients (-1)^k / (2k+1).
        const std::array<double, 8> atan_ratio = {{1.0, -1.0 / 3, 1.0 / 5,
                                                   -1.0 / 7, 1.0 / 9, -1.0 / 11,
                                                   1.0 / 13, -1.0 / 15}};
        const T                     x_squared  = s_squared / (q[0] * q[0]);
        factor = 2.0 / q[0] * power_series(x_squared, atan_ratio);
      }
      else
      {
        const T s = sqrt(s_squared);
        factor    = 2.0 * atan2(s, q[0]) / s;
      }
      return scaled(factor, v);
    }

    // ---- co-rotated frame --------------------------------------------------

    template<typename T>
    struct CorotatedConfiguration
    {
      Mat3<T>                         axes;         ///< rows e1, e2, e3
      std::array<std::array<T, 2>, 3> translations; ///< deformational (u, v)
    };

    // e3 is the current normal. In-plane, the frame is turned by the polar
    // rotation of the (constant) deformation gradient F from the initial to
    // the current coordinates, so that it does not depend on which vertex
    // comes first and carries E0 rigidly at zero strain.
    template<typename T>
    CorotatedConfiguration<T> corotate(const CorotationalReference  &reference,
                                       const std::array<Vec3<T>, 3> &x)
    {
      using std::atan2;
      using std::cos;
      using std::sin;
      const Vec3<T> edge_1 = x[1] - x[0];
      const Vec3<T> edge_2 = x[2] - x[0];
      const Vec3<T> e3     = normalized(cross(edge_1, edge_2));
      const Vec3<T> t1     = normalized(edge_1);
      const Vec3<T> t2     = cross(e3, t1);

      // Coordinates in (t1, t2) about the centroid.
      Vec3<T> centroid;
      for (unsigned int c = 0; c < 3; ++c)
        centroid[c] = (x[0][c] + x[1][c] + x[2][c]) / 3.0;
      std::array<std::array<T, 2>, 3> y;
      for (unsigned int i = 0; i < 3; ++i)
      {
        const Vec3<T> offset = x[i] - centroid;
        y[i]                 = {{dot(offset, t1), dot(offset, t2)}};
      }

      // F = [y1 - y0, y2 - y0] [X1 - X0, X2 - X0]^-1 and its polar angle.
      const auto &inverse = reference.inverse_edges;
      T           f[2][2];
      for (unsigned int a = 0; a < 2; ++a)
        for (unsigned int b = 0; b < 2; ++b)
          f[a][b] = (y[1][a] - y[0][a]) * inverse[0][b] +
                    (y[2][a] - y[0][a]) * inverse[1][b];
      const T angle = atan2(f[1][0] - f[0][1], f[0][0] + f[1][1]);
      const T c = cos(angle), s = sin(angle);

      CorotatedConfiguration<T> result;
      for (unsigned int r = 0; r < 3; ++r)
      {
        result.axes[0][r] = c * t1[r] + s * t2[r];
        result.axes[1][r] = c * t2[r] - s * t1[r];
      }
      result.axes[2] = e3;
      for (unsigned int i = 0; i < 3; ++i)
      {
        const Point<2> &initial   = reference.coordinates[i];
        result.translations[i][0] = c * y[i][0] + s * y[i][1] - initial[0];
        result.translations[i][1] = c * y[i][1] - s * y[i][0] - initial[1];
      }
      return result;
    }

    // The current triad of a node, R_i E0, as a matrix with the triad
    // vectors as columns.
    Mat3<double> nodal_triad(const Tensor<2, 3>          &rotation,
                             const CorotationalReference &reference)
    {
      Mat3<double> triad;
      for (unsigned int b = 0; b < 3; ++b)
      {
        const Tensor<1, 3> column = rotation * reference.frame.axes[b];
        for (unsigned int r = 0; r < 3; ++r)
          triad[r][b] = column[r];
      }
      return triad;
    }

    // ---- the deformational rotation of a node ------------------------------
    //
    // With E^T = A (rows of the co-rotated frame) and the node's triad
    // B = R_i E0, the deformational rotation after the frame is spun by
    // omega and the node rotated by theta is
    //   psi(omega, theta) = log(A exp(-omega) exp(theta) B)
    //                     = F(A phi),  F(phi') = log(exp(phi') A B),
    // with phi = theta - omega - 1/2 omega x theta + O(3) (Baker-Campbell-
    // Hausdorff) and A exp(phi) = exp(A phi) A. F has the closed-form
    // derivatives below, so no AD is spent on rotations.

    /// c(t) = (1 - (t/2) cot(t/2)) / t^2, the coefficient of skew(psi)^2 in
    /// the inverse left Jacobian of SO(3), and c'(t) / t.
    struct InverseJacobianCoefficient
    {
      double value;
      double derivative_over_angle;
    };

    InverseJacobianCoefficient inverse_jacobian_coefficient(double t)
    {
      const double t2 = t * t;
      // The closed forms cancel: c to about 1e-16 / t^2 relative, c'/t to
      // 1e-16 / t^4. Below 0.2 rad the series (from the Bernoulli numbers
      // of x cot x) are used; their first omitted terms are below 1e-11
      // relative there.
      if (t < 0.2)
        return {
            1.0 / 12 +
                t2 * (1.0 / 720 + t2 * (1.0 / 30240 +
                                        t2 * (1.0 / 1209600 + t2 / 47900160))),
            1.0 / 360 + t2 * (1.0 / 7560 + t2 * (1.0 / 201600 + t2 / 5987520))};
      const double half = 0.5 * t, sine = std::sin(half);
      const double cotangent_term = half * std::cos(half) / sine; // q(t)
      const double cotangent_derivative =
          0.5 * std::cos(half) / sine - 0.25 * t / (sine * sine); // q'(t)
      return {(1.0 - cotangent_term) / t2,
              -cotangent_derivative / (t2 * t) -
                  2.0 * (1.0 - cotangent_term) / (t2 * t2)};
    }

    Mat3<double> skew_matrix(const Vec3<double> &a)
    {
      return {
          {{{0.0, -a[2], a[1]}}, {{a[2], 0.0, -a[0]}}, {{-a[1], a[0], 0.0}}}};
    }

    Mat3<double> transposed(const Mat3<double> &a)
    {
      Mat3<double> t;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          t[i][j] = a[j][i];
      return t;
    }

    Vec3<double> transpose_times(const Mat3<double> &a, const Vec3<double> &v)
    {
      Vec3<double> result{};
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          result[j] += a[i][j] * v[i];
      return result;
    }

    /// The deformational rotation of one node and its first derivatives:
    /// d psi / d theta = M A and d psi / d omega = -M A, M = J_l^{-1}(psi)
    /// (since exp(phi' + dphi') = exp(J_l(phi') dphi') exp(phi')).
    struct NodalRotationDerivatives
    {
      Vec3<double> value;
      Mat3<double> inverse_jacobian; ///< M
      Mat3<double> gradient;         ///< M A
    };

    /// The Hessian in (omega, theta) of w . psi at 0 (6 x 6, symmetric).
    /// With u = M^T w, the gradient of w . F at 0, F's Hessian is
    ///   H' = 1/2 skew(u) + D M,  D = d(J_l^{-1}(psi)^T w) / d psi
    /// (the first term from J_l(phi') = I + 1/2 skew(phi') + ...); the
    /// linear part of phi maps it through A [-I, I], the BCH term adds
    /// +-1/2 skew(A^T u) to the mixed blocks.
    std::array<std::array<double, 6>, 6>
    rotation_hessian(const NodalRotationDerivatives &rotation,
                     const Mat3<double>             &frame,
                     const Vec3<double>             &w)
    {
      const Vec3<double> &psi   = rotation.value;
      const Vec3<double>  u     = transpose_times(rotation.inverse_jacobian, w);
      const double        t2    = dot(psi, psi);
      const double        psi_w = dot(psi, w);
      const auto coefficient    = inverse_jacobian_coefficient(std::sqrt(t2));

      // D = -1/2 skew(w) + c (psi.w I + psi w^T - 2 w psi^T)
      //     + c'/t (psi (psi.w) - t^2 w) psi^T.
      Mat3<double> d = skew_matrix(scaled(-0.5, w));
      for (unsigned int i = 0; i < 3; ++i)
      {
        d[i][i] += coefficient.value * psi_w;
        const double radial =
            coefficient.derivative_over_angle * (psi[i] * psi_w - t2 * w[i]);
        for (unsigned int j = 0; j < 3; ++j)
          d[i][j] += coefficient.value * (psi[i] * w[j] - 2.0 * w[i] * psi[j]) +
                     radial * psi[j];
      }
      Mat3<double>       h_local     = product(d, rotation.inverse_jacobian);
      const Mat3<double> half_skew_u = skew_matrix(scaled(0.5, u));
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          h_local[i][j] += half_skew_u[i][j];
      const Mat3<double> h =
          product(transposed(frame), product(h_local, frame));
      const Mat3<double> bch =
          skew_matrix(scaled(0.5, transpose_times(frame, u)));

      std::array<std::array<double, 6>, 6> hessian;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
        {
          hessian[i][j] = hessian[3 + i][3 + j] = h[i][j];
          hessian[i][3 + j]                     = -h[i][j] + bch[i][j];
          hessian[3 + i][j]                     = -h[i][j] - bch[i][j];
        }
      return hessian;
    }

    // ---- deformational DOFs and their derivatives -------------------------

    /// Index of translation component k = 3 * vertex + c among the 18 DOFs.
    constexpr unsigned int translation_dof(unsigned int k)
    {
      return 6 * (k / 3) + k % 3;
    }

    constexpr unsigned int rotation_dof(unsigned int vertex, unsigned int c)
    {
      return 6 * vertex + 3 + c;
    }

    using Matrix18 = std::array<std::array<double, shell_dofs>, shell_dofs>;

    // ---- derivatives of the frame and the translations in the edges -------
    //
    // The co-rotated frame and the in-plane translations depend on the
    // vertices only through the edges a = x1 - x0 and b = x2 - x0 (a rigid
    // translation moves neither): d/dx_v = sum_e edge_weight[v][e] d/de_e.
    // They are differentiated in closed form at the current configuration
    // (doc/theory/corotational.md, section 13.4):
    // - the translations and the polar angle theta of the frame in the
    //   edge frame (t1 = a/|a|, t2 = n x t1) are invariant to rotations, so
    //   they depend on (a, b) only through (A, B, C) = (a.a, b.b, a.b);
    //   they are differentiated in those three scalars (forward AD of a
    //   dozen scalar operations) and chained;
    // - the spin omega of the frame, E(u) = exp(skew(omega)) E, is to
    //   second order omega = n0 x n + chi n0 + 1/2 chi (n - (n.n0) n0),
    //   with n the unit normal and chi = psi + theta - theta0 the in-plane
    //   turn about it: psi, the turn of t1 from its minimal-rotation
    //   transport, is t2_0.t1 - (n0.t1)(t2_0.n) - 1/2 (t1_0.n)(t2_0.n) to
    //   second order.
    constexpr double edge_weight[3][2] = {{-1.0, -1.0}, {1.0, 0.0}, {0.0, 1.0}};

    void require_nondegenerate(const SpatialTriangle &current)
    {
      make_element_frame(current); // throws DegenerateTriangle
    }

    /// A gradient (d/da, d/db) and a Hessian in the six edge components.
    using EdgeVector = std::array<double, 6>;
    using EdgeMatrix = std::array<std::array<double, 6>, 6>;

    /// Forward AD in the invariants (A, B, C), to first or second order.
    template<int order>
    struct InvariantJet;

    template<>
    struct InvariantJet<1>
    {
      using type = Sacado::Fad::SFad<double, 3>;
      static type variable(double value, int k)
      {
        return type(3, k, value);
      }
      static void set_value(type &x, double value)
      {
        x.val() = value;
      }
      static double derivative(const type &x, int k)
      {
        return x.dx(k);
      }
    };

    template<>
    struct InvariantJet<2>
    {
      using inner = Sacado::Fad::SFad<double, 3>;
      using type  = Sacado::Fad::SFad<inner, 3>;
      static type variable(double value, int k)
      {
        return type(3, k, inner(3, k, value));
      }
      static void set_value(type &x, double value)
      {
        x.val().val() = value;
      }
      static double derivative(const type &x, int k)
      {
        return x.val().dx(k);
      }
      static double second_derivative(const type &x, int k, int l)
      {
        return x.dx(k).dx(l);
      }
    };

    template<typename T>
    struct PlanarState
    {
      T                               angle; ///< theta, in the edge frame
      std::array<std::array<T, 2>, 3> translations;
    };

    /// corotate() restated in the invariants: the vertices in the edge
    /// frame are (0, 0), (|a|, 0), (C/|a|, |a x b|/|a|). |a x b|^2 takes
    /// its value from the cross product (A B - C^2 cancels on slivers) and
    /// its derivatives from A B - C^2.
    template<int order>
    PlanarState<typename InvariantJet<order>::type>
    planar_state(const CorotationalReference &reference,
                 const Vec3<double>          &a,
                 const Vec3<double>          &b,
                 double                       cross_squared)
    {
      using Jet = InvariantJet<order>;
      using T   = typename Jet::type;
      using std::atan2;
      using std::cos;
      using std::sin;
      using std::sqrt;
      const T A         = Jet::variable(dot(a, a), 0);
      const T B         = Jet::variable(dot(b, b), 1);
      const T C         = Jet::variable(dot(a, b), 2);
      T       area_term = A * B - C * C;
      Jet::set_value(area_term, cross_squared);
      const T length = sqrt(A);
      const T b1     = C / length;
      const T b2     = sqrt(area_term) / length;

      const T                         cx = (length + b1) / 3.0, cy = b2 / 3.0;
      std::array<std::array<T, 2>, 3> y;
      y[0]                = {{-cx, -cy}};
      y[1]                = {{length - cx, -cy}};
      y[2]                = {{b1 - cx, b2 - cy}};
      const auto &inverse = reference.inverse_edges;
      const T     f00     = length * inverse[0][0] + b1 * inverse[1][0];
      const T     f01     = length * inverse[0][1] + b1 * inverse[1][1];
      const T     f10     = b2 * inverse[1][0];
      const T     f11     = b2 * inverse[1][1];

      PlanarState<T> state;
      state.angle = atan2(f10 - f01, f00 + f11);
      const T c = cos(state.angle), s = sin(state.angle);
      for (unsigned int i = 0; i < 3; ++i)
      {
        const Point<2> &initial  = reference.coordinates[i];
        state.translations[i][0] = c * y[i][0] + s * y[i][1] - initial[0];
        state.translations[i][1] = c * y[i][1] - s * y[i][0] - initial[1];
      }
      return state;
    }

    /// A function of (A, B, C): its gradient and (order 2) Hessian there.
    struct InvariantDerivatives
    {
      Vec3<double> gradient{};
      Mat3<double> hessian{};
    };

    template<int order>
    InvariantDerivatives
    invariant_derivatives(const typename InvariantJet<order>::type &x)
    {
      InvariantDerivatives result;
      for (int k = 0; k < 3; ++k)
      {
        result.gradient[k] = InvariantJet<order>::derivative(x, k);
        if constexpr (order == 2)
          for (int l = 0; l < 3; ++l)
            result.hessian[k][l] =
                InvariantJet<order>::second_derivative(x, k, l);
      }
      return result;
    }

    EdgeVector edge_vector(const Vec3<double> &da, const Vec3<double> &db)
    {
      return {{da[0], da[1], da[2], db[0], db[1], db[2]}};
    }

    /// h += factor (u v^T + v u^T).
    void add_symmetric_product(double            factor,
                               const EdgeVector &u,
                               const EdgeVector &v,
                               EdgeMatrix       &h)
    {
      for (unsigned int k = 0; k < 6; ++k)
        for (unsigned int l = 0; l < 6; ++l)
          h[k][l] += factor * (u[k] * v[l] + v[k] * u[l]);
    }

    /// The derivatives of the frame's spin and of the translations in the
    /// edges, order 1 (gradients) or 2 (and weighted Hessians).
    template<int order>
    class EdgeDerivatives
    {
    public:
      EdgeDerivatives(const CorotationalReference &reference,
                      const SpatialTriangle       &current)
      {
        for (unsigned int c = 0; c < 3; ++c)
        {
          a[c] = current[1][c] - current[0][c];
          b[c] = current[2][c] - current[0][c];
        }
        length               = std::sqrt(dot(a, a));
        t1                   = scaled(1.0 / length, a);
        const Vec3<double> c = cross(a, b);
        cross_length         = std::sqrt(dot(c, c));
        n                    = scaled(1.0 / cross_length, c);
        t2                   = cross(n, t1);
        invariant_gradients  = {{edge_vector(scaled(2.0, a), {}),
                                 edge_vector({}, scaled(2.0, b)),
                                 edge_vector(b, a)}};

        const auto planar = planar_state<order>(reference, a, b, dot(c, c));
        angle             = invariant_derivatives<order>(planar.angle);
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int k = 0; k < 2; ++k)
          {
            translation[i][k] =
                invariant_derivatives<order>(planar.translations[i][k]);
            translation_gradients[i][k] = chain(translation[i][k].gradient);
          }

        turn_gradient = chain(angle.gradient);
        for (unsigned int k = 0; k < 3; ++k)
          turn_gradient[k] += t2[k] / length; // d psi
        for (unsigned int k = 0; k < 6; ++k)
        {
          const Vec3<double> dn     = normal_derivative(k);
          const Vec3<double> n_x_dn = cross(n, dn);
          for (unsigned int m = 0; m < 3; ++m)
            spin_gradients[m][k] = n_x_dn[m] + n[m] * turn_gradient[k];
        }
      }

      const EdgeVector &translation_gradient(unsigned int i,
                                             unsigned int k) const
      {
        return translation_gradients[i][k];
      }

      const EdgeVector &spin_gradient(unsigned int m) const
      {
        return spin_gradients[m];
      }

      /// h += sum w_ik d^2 t_ik + sum s_m d^2 omega_m (order 2 only).
      void add_weighted_hessian(const std::array<std::array<double, 2>, 3> &w,
                                const Vec3<double>                         &s,
                                EdgeMatrix &h) const
      {
        static_assert(order == 2, "second derivatives need order 2");
        const double s_normal = dot(s, n);
        // The invariant functions: the translations and theta (in chi).
        InvariantDerivatives sum;
        for (unsigned int p = 0; p < 3; ++p)
        {
          sum.gradient[p] = s_normal * angle.gradient[p];
          for (unsigned int q = 0; q < 3; ++q)
            sum.hessian[p][q] = s_normal * angle.hessian[p][q];
        }
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int k = 0; k < 2; ++k)
            for (unsigned int p = 0; p < 3; ++p)
            {
              sum.gradient[p] += w[i][k] * translation[i][k].gradient[p];
              for (unsigned int q = 0; q < 3; ++q)
                sum.hessian[p][q] += w[i][k] * translation[i][k].hessian[p][q];
            }
        add_invariant_hessian(sum, h);

        // (s.n0) psi_uu.
        const EdgeVector t2_normal = normal_gradient(t2);
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int l = 0; l < 3; ++l)
            h[k][l] -=
                s_normal * (t2[k] * t1[l] + t1[k] * t2[l]) / (length * length);
        add_symmetric_product(
            -s_normal, edge_vector(scaled(1.0 / length, n), {}), t2_normal, h);
        add_symmetric_product(-0.5 * s_normal, normal_gradient(t1), t2_normal,
                              h);

        // s . (n0 x n) = (s x n0) . n, and 1/2 chi (s . P n), P = I - n0 n0^T.
        add_normal_hessian(cross(s, n), h);
        add_symmetric_product(0.5, turn_gradient,
                              normal_gradient(s - scaled(s_normal, n)), h);
      }

    private:
      /// Gradient in the edges of f(A, B, C) from its invariant gradient.
      EdgeVector chain(const Vec3<double> &f) const
      {
        EdgeVector g{};
        for (unsigned int p = 0; p < 3; ++p)
          for (unsigned int k = 0; k < 6; ++k)
            g[k] += f[p] * invariant_gradients[p][k];
        return g;
      }

      /// h += the edge Hessian of f(A, B, C): the invariants' gradients
      /// through f's Hessian, and f's gradient through the invariants'
      /// constant Hessians (2 I, 2 I and the identity across a and b).
      void add_invariant_hessian(const InvariantDerivatives &f,
                                 EdgeMatrix                 &h) const
      {
        for (unsigned int p = 0; p < 3; ++p)
          for (unsigned int q = 0; q < 3; ++q)
            for (unsigned int k = 0; k < 6; ++k)
              for (unsigned int l = 0; l < 6; ++l)
                h[k][l] += f.hessian[p][q] * invariant_gradients[p][k] *
                           invariant_gradients[q][l];
        for (unsigned int c = 0; c < 3; ++c)
        {
          h[c][c] += 2.0 * f.gradient[0];
          h[3 + c][3 + c] += 2.0 * f.gradient[1];
          h[c][3 + c] += f.gradient[2];
          h[3 + c][c] += f.gradient[2];
        }
      }

      /// d n / d e_k: the normal's change under a unit change of edge
      /// component k (a for k < 3, b above).
      Vec3<double> normal_derivative(unsigned int k) const
      {
        Vec3<double> unit{};
        unit[k % 3]             = 1.0;
        const Vec3<double> dc   = k < 3 ? cross(unit, b) : cross(a, unit);
        const double       dc_n = dot(dc, n);
        return scaled(1.0 / cross_length, dc - scaled(dc_n, n));
      }

      /// The edge gradient of v . n for v normal to n.
      EdgeVector normal_gradient(const Vec3<double> &v) const
      {
        return edge_vector(scaled(1.0 / cross_length, cross(b, v)),
                           scaled(1.0 / cross_length, cross(v, a)));
      }

      /// h += the edge Hessian of v . n for v normal to n, through
      /// c = a x b: J_c^T H_c J_c with H_c = -(v n^T + n v^T)/|c|^2, and
      /// the bilinearity of c, -skew(v)/|c| in the (a, b) block.
      void add_normal_hessian(const Vec3<double> &v, EdgeMatrix &h) const
      {
        const double inverse = 1.0 / cross_length;
        add_symmetric_product(-inverse * inverse,
                              edge_vector(cross(b, v), cross(v, a)),
                              edge_vector(cross(b, n), cross(n, a)), h);
        const Mat3<double> skew_v = skew_matrix(scaled(inverse, v));
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int l = 0; l < 3; ++l)
          {
            h[k][3 + l] -= skew_v[k][l];
            h[3 + l][k] -= skew_v[k][l];
          }
      }

      Vec3<double>              a, b, t1, t2, n;
      double                    length, cross_length;
      std::array<EdgeVector, 3> invariant_gradients; ///< of A, B, C
      InvariantDerivatives      angle;
      std::array<std::array<InvariantDerivatives, 2>, 3> translation;
      std::array<std::array<EdgeVector, 2>, 3>           translation_gradients;
      EdgeVector                turn_gradient;  ///< of chi
      std::array<EdgeVector, 3> spin_gradients; ///< of omega
    };

    // d and its derivatives with respect to the perturbation p at p = 0:
    // the edges drive the frame and the in-plane translations (closed
    // form, above); each node's rotation is differentiated in closed form
    // with respect to (omega, theta_i) and chained with the derivatives of
    // omega(u). Order 0 gives d alone.
    template<int order>
    class CorotatedKinematics
    {
    public:
      CorotatedKinematics(const CorotationalReference &reference,
                          const SpatialTriangle       &current,
                          const NodalRotations        &rotations)
          : edges(make_edge_derivatives(reference, current))
      {
        std::array<Vec3<double>, 3> x;
        for (unsigned int v = 0; v < 3; ++v)
          for (unsigned int c = 0; c < 3; ++c)
            x[v][c] = current[v][c];
        const CorotatedConfiguration<double> configuration =
            corotate(reference, x);
        translations = configuration.translations;
        axes         = configuration.axes;

        for (unsigned int i = 0; i < 3; ++i)
        {
          NodalRotationDerivatives &rotation = nodal_rotations[i];
          rotation.value =
              log_map(product(axes, nodal_triad(rotations[i], reference)));
          if constexpr (order > 0)
          {
            const Vec3<double> &psi   = rotation.value;
            rotation.inverse_jacobian = to_mat3(so3_left_jacobian_inverse(
                Tensor<1, 3>({psi[0], psi[1], psi[2]})));
            rotation.gradient = product(rotation.inverse_jacobian, axes);
          }
        }
      }

      /// Rows e1, e2, e3 of the current co-rotated frame.
      const Mat3<double> &frame() const
      {
        return axes;
      }

      ShellDisplacements dofs() const
      {
        ShellDisplacements d{};
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int c = 0; c < 3; ++c)
          {
            if (c < 2)
              d[6 * i + c] = translations[i][c];
            d[rotation_dof(i, c)] = nodal_rotations[i].value[c];
          }
        return d;
      }

      /// J = dd/dp (18 x 18); the rows of w are zero.
      void jacobian(Matrix18 &j) const
      {
        static_assert(order > 0, "the Jacobian needs order 1 or 2");
        j = {};
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int c = 0; c < 2; ++c)
          {
            const auto gradient =
                vertex_gradient(edges->translation_gradient(i, c));
            for (unsigned int k = 0; k < 9; ++k)
              j[6 * i + c][translation_dof(k)] = gradient[k];
          }

        const auto spin_gradient = spin_vertex_gradient();
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int a = 0; a < 3; ++a)
          {
            const Vec3<double> &row = nodal_rotations[i].gradient[a];
            for (unsigned int k = 0; k < 9; ++k)
              j[rotation_dof(i, a)][translation_dof(k)] = -(
                  row[0] * spin_gradient[0][k] + row[1] * spin_gradient[1][k] +
                  row[2] * spin_gradient[2][k]);
            for (unsigned int b = 0; b < 3; ++b)
              j[rotation_dof(i, a)][rotation_dof(i, b)] = row[b];
          }
      }

      /// h += sum_k weights_k d^2 d_k / dp^2 (order 2 only).
      void add_weighted_hessian(const ShellDisplacements &weights,
                                Matrix18                 &h) const
      {
        static_assert(order == 2, "second derivatives need order 2");
        std::array<std::array<double, 2>, 3> translation_weights;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int c = 0; c < 2; ++c)
            translation_weights[i][c] = weights[6 * i + c];
        const auto   spin_gradient = spin_vertex_gradient();
        Vec3<double> spin_weights{};
        for (unsigned int i = 0; i < 3; ++i)
          add_rotation_hessian(i, weights, spin_gradient, spin_weights, h);
        EdgeMatrix edge_hessian{};
        edges->add_weighted_hessian(translation_weights, spin_weights,
                                    edge_hessian);

        // H_x = L^T H_e L block by block, L = edge_weight.
        for (unsigned int v = 0; v < 3; ++v)
          for (unsigned int w = 0; w < 3; ++w)
            for (unsigned int e = 0; e < 2; ++e)
              for (unsigned int f = 0; f < 2; ++f)
              {
                const double weight = edge_weight[v][e] * edge_weight[w][f];
                if (weight == 0.0)
                  continue;
                for (unsigned int c = 0; c < 3; ++c)
                  for (unsigned int d = 0; d < 3; ++d)
                    h[6 * v + c][6 * w + d] +=
                        weight * edge_hessian[3 * e + c][3 * f + d];
              }
      }

    private:
      using SpinGradient = std::array<std::array<double, 9>, 3>;

      static std::optional<EdgeDerivatives<order>>
      make_edge_derivatives(const CorotationalReference &reference,
                            const SpatialTriangle       &current)
      {
        require_nondegenerate(current);
        if constexpr (order == 0)
          return std::nullopt;
        else
          return EdgeDerivatives<order>(reference, current);
      }

      static std::array<double, 9> vertex_gradient(const EdgeVector &edge)
      {
        std::array<double, 9> gradient;
        for (unsigned int c = 0; c < 3; ++c)
        {
          gradient[c]     = -edge[c] - edge[3 + c];
          gradient[3 + c] = edge[c];
          gradient[6 + c] = edge[3 + c];
        }
        return gradient;
      }

      /// Omega = d omega / du (3 x 9).
      SpinGradient spin_vertex_gradient() const
      {
        SpinGradient gradient;
        for (unsigned int m = 0; m < 3; ++m)
          gradient[m] = vertex_gradient(edges->spin_gradient(m));
        return gradient;
      }

      // Chain rule through omega(u) for psi = sum_a w_a theta_d,a(omega,
      // theta): psi_uu = Omega^T psi_ww Omega + psi_w . omega_uu, psi_ut =
      // Omega^T psi_wt, with Omega = d omega / du. The omega_uu term is
      // gathered as weights of the spin (spin_weights).
      void add_rotation_hessian(unsigned int              i,
                                const ShellDisplacements &weights,
                                const SpinGradient       &omega,
                                Vec3<double>             &spin_weights,
                                Matrix18                 &h) const
      {
        const Vec3<double>              w = {{weights[rotation_dof(i, 0)],
                                              weights[rotation_dof(i, 1)],
                                              weights[rotation_dof(i, 2)]}};
        const NodalRotationDerivatives &rotation = nodal_rotations[i];
        const auto psi_hessian = rotation_hessian(rotation, axes, w);
        // d psi / d omega = -M A.
        const Vec3<double> psi_spin = transpose_times(rotation.gradient, w);
        for (unsigned int m = 0; m < 3; ++m)
          spin_weights[m] -= psi_spin[m];

        // Omega^T psi_w. over the 6 columns (omega, theta).
        double mixed[9][6] = {};
        for (unsigned int k = 0; k < 9; ++k)
          for (unsigned int n = 0; n < 6; ++n)
            for (unsigned int m = 0; m < 3; ++m)
              mixed[k][n] += omega[m][k] * psi_hessian[m][n];

        for (unsigned int k = 0; k < 9; ++k)
        {
          for (unsigned int l = 0; l < 9; ++l)
            h[translation_dof(k)][translation_dof(l)] +=
                mixed[k][0] * omega[0][l] + mixed[k][1] * omega[1][l] +
                mixed[k][2] * omega[2][l];
          for (unsigned int b = 0; b < 3; ++b)
          {
            h[translation_dof(k)][rotation_dof(i, b)] += mixed[k][3 + b];
            h[rotation_dof(i, b)][translation_dof(k)] += mixed[k][3 + b];
          }
        }
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int b = 0; b < 3; ++b)
            h[rotation_dof(i, a)][rotation_dof(i, b)] +=
                psi_hessian[3 + a][3 + b];
      }

      std::optional<EdgeDerivatives<order>>   edges;
      std::array<std::array<double, 2>, 3>    translations{};
      std::array<NodalRotationDerivatives, 3> nodal_rotations{};
      Mat3<double>                            axes{};
    };

    // ---- forces and tangents ----------------------------------------------

    dealii::Vector<double> to_vector(const ShellDisplacements &a)
    {
      return dealii::Vector<double>(a.begin(), a.end());
    }

    // g = K_l d, the force conjugate to the deformational DOFs.
    ShellDisplacements local_force(const FullMatrix<double> &stiffness,
                                   const ShellDisplacements &d)
    {
      ShellDisplacements g{};
      for (unsigned int a = 0; a < shell_dofs; ++a)
        for (unsigned int b = 0; b < shell_dofs; ++b)
          g[a] += stiffness(a, b) * d[b];
      return g;
    }

    // f = J^T g.
    ShellDisplacements jacobian_transpose_times(const Matrix18           &j,
                                                const ShellDisplacements &g)
    {
      ShellDisplacements f{};
      for (unsigned int a = 0; a < shell_dofs; ++a)
        for (unsigned int b = 0; b < shell_dofs; ++b)
          f[b] += j[a][b] * g[a];
      return f;
    }

    constexpr bool is_rotation(unsigned int dof)
    {
      return dof % 6 >= 3;
    }

    // J^T K_l J, using the shape of J: the rows of w are zero, and a
    // rotation row of node i has entries only in the translation columns
    // and in node i's rotation columns. The result is symmetric.
    void congruence(const FullMatrix<double> &stiffness,
                    const Matrix18           &j,
                    Matrix18                 &result)
    {
      constexpr std::array<unsigned int, 15> rows = {
          {0, 1, 3, 4, 5, 6, 7, 9, 10, 11, 12, 13, 15, 16, 17}};
      // K J, column by column.
      Matrix18 k_j;
      for (unsigned int b = 0; b < shell_dofs; ++b)
      {
        const unsigned int first = is_rotation(b) ? 6 * (b / 6) + 3 : 0;
        for (unsigned int a = 0; a < shell_dofs; ++a)
        {
          double sum = 0.0;
          if (is_rotation(b))
            for (unsigned int c = first; c < first + 3; ++c)
              sum += stiffness(a, c) * j[c][b];
          else
            for (const unsigned int c : rows)
              sum += stiffness(a, c) * j[c][b];
          k_j[a][b] = sum;
        }
      }
      // J^T (K J), upper triangle.
      for (unsigned int a = 0; a < shell_dofs; ++a)
      {
        const unsigned int first = is_rotation(a) ? 6 * (a / 6) + 3 : 0;
        for (unsigned int b = a; b < shell_dofs; ++b)
        {
          double sum = 0.0;
          if (is_rotation(a))
            for (unsigned int c = first; c < first + 3; ++c)
              sum += j[c][a] * k_j[c][b];
          else
            for (const unsigned int c : rows)
              sum += j[c][a] * k_j[c][b];
          result[a][b] = result[b][a] = sum;
        }
      }
    }

    // Under R <- exp(a) R the force at a state already updated by exp(b)
    // sees exp(a) exp(b) = exp(a + b + a x b / 2 + ...), so d f_a / d b
    // gains 1/2 eps_kab m_k = -1/2 skew(m)_ab on each node's rotation block,
    // m being that node's moment.
    void add_rotation_update_term(const ShellDisplacements &force,
                                  Matrix18                 &tangent)
    {
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int a = 0; a < 3; ++a)
        {
          const unsigned int b = (a + 1) % 3, k = (a + 2) % 3;
          const double       half_moment = 0.5 * force[rotation_dof(i, k)];
          tangent[rotation_dof(i, a)][rotation_dof(i, b)] += half_moment;
          tangent[rotation_dof(i, b)][rotation_dof(i, a)] -= half_moment;
        }
    }

    // K <- (K + K^T) / 2. The consistent tangent is symmetric at
    // equilibrium (Felippa & Haugen 2005); away from it the skew part is
    // what the symmetric variant gives up for a Cholesky solve.
    void symmetrize(Matrix18 &tangent)
    {
      for (unsigned int i = 0; i < shell_dofs; ++i)
        for (unsigned int j = i + 1; j < shell_dofs; ++j)
          tangent[i][j] = tangent[j][i] = 0.5 * (tangent[i][j] + tangent[j][i]);
    }

    void copy_to(const Matrix18 &source, FullMatrix<double> &target)
    {
      if (target.m() != shell_dofs || target.n() != shell_dofs)
        target.reinit(shell_dofs, shell_dofs);
      for (unsigned int i = 0; i < shell_dofs; ++i)
        std::copy(source[i].begin(), source[i].end(), &target(i, 0));
    }

    std::array<Tensor<1, 3>, 3> as_tensors(const Mat3<double> &e)
    {
      std::array<Tensor<1, 3>, 3> axes;
      for (unsigned int a = 0; a < 3; ++a)
        axes[a] = Tensor<1, 3>({e[a][0], e[a][1], e[a][2]});
      return axes;
    }

    CorotationalReference make_reference(const SpatialTriangle &initial)
    {
      CorotationalReference reference;
      reference.frame         = make_element_frame(initial);
      const auto    &planar   = reference.frame.planar;
      const Point<2> centroid = (planar[0] + planar[1] + planar[2]) / 3.0;
      for (unsigned int i = 0; i < 3; ++i)
        reference.coordinates[i] = Point<2>(planar[i] - centroid);

      const Tensor<1, 2> edge_1 = planar[1] - planar[0];
      const Tensor<1, 2> edge_2 = planar[2] - planar[0];
      const double       det    = edge_1[0] * edge_2[1] - edge_2[0] * edge_1[1];
      reference.inverse_edges   = {{{{edge_2[1] / det, -edge_2[0] / det}},
                                    {{-edge_1[1] / det, edge_1[0] / det}}}};
      return reference;
    }
  } // namespace

  CorotationalShell::CorotationalShell(const SpatialTriangle     &initial,
                                       const ShellMaterial       &material,
                                       const ShellElementOptions &options)
      : reference(make_reference(initial)),
        stiffness(shell_stiffness_local(reference.frame, material, options)),
        recovery(reference.frame.planar, material, options)
  {
  }

  ShellDisplacements
  CorotationalShell::deformational_dofs(const SpatialTriangle &current,
                                        const NodalRotations  &rotations) const
  {
    return CorotatedKinematics<0>(reference, current, rotations).dofs();
  }

  double CorotationalShell::energy(const SpatialTriangle &current,
                                   const NodalRotations  &rotations) const
  {
    const dealii::Vector<double> d =
        to_vector(deformational_dofs(current, rotations));
    return 0.5 * stiffness.matrix_norm_square(d);
  }

  void CorotationalShell::internal_force(
      const SpatialTriangle     &current,
      const NodalRotations      &rotations,
      CorotationalTangent        tangent_type,
      ShellDisplacements        &force,
      FullMatrix<double>        *tangent,
      const ShellDisplacements  *geometric_dofs,
      CorotationalLinearization *linearization) const
  {
    if (tangent != nullptr && tangent_type != CorotationalTangent::paper)
    {
      // K = J^T K_l J + sum_k g_k d^2 d_k/dp^2 + rotation-update term,
      // with g = K_l d and f = J^T g.
      const CorotatedKinematics<2> jets(reference, current, rotations);
      Matrix18                     j;
      jets.jacobian(j);
      const ShellDisplacements d = jets.dofs();
      const ShellDisplacements g = local_force(stiffness, d);
      force                      = jacobian_transpose_times(j, g);
      Matrix18 k;
      congruence(stiffness, j, k);
      if (geometric_dofs == nullptr)
      {
        jets.add_weighted_hessian(g, k);
        add_rotation_update_term(force, k);
      }
      else
      {
        const ShellDisplacements g_geometric =
            local_force(stiffness, *geometric_dofs);
        jets.add_weighted_hessian(g_geometric, k);
        add_rotation_update_term(jacobian_transpose_times(j, g_geometric), k);
      }
      if (tangent_type == CorotationalTangent::symmetric)
        symmetrize(k);
      copy_to(k, *tangent);
      if (linearization != nullptr)
        *linearization = {d, j};
      return;
    }

    const CorotatedKinematics<1> jets(reference, current, rotations);
    Matrix18                     j;
    jets.jacobian(j);
    force = jacobian_transpose_times(j, local_force(stiffness, jets.dofs()));
    if (tangent != nullptr)
    {
      // The paper's tangent: K_l rotated along the current frame only.
      rotate_to_global(stiffness, as_tensors(jets.frame()), *tangent);
    }
  }

  ShellResultants
  CorotationalShell::resultants(const SpatialTriangle &current,
                                const NodalRotations  &rotations) const
  {
    // The initial shape carried rigidly onto the current frame has that
    // frame as its element frame and the initial planar coordinates: the
    // linear resultants of d on the initial shape, with the current axes.
    const CorotatedKinematics<0> state(reference, current, rotations);
    return recovery.resultants(as_tensors(state.frame()), state.dofs());
  }

  Tensor<2, 3> rotation_exp(const Tensor<1, 3> &theta)
  {
    const Mat3<double> r =
        exp_map(Vec3<double>{{theta[0], theta[1], theta[2]}});
    Tensor<2, 3> result;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        result[i][j] = r[i][j];
    return result;
  }

  Tensor<1, 3> rotation_log(const Tensor<2, 3> &rotation)
  {
    const Vec3<double> theta = log_map(to_mat3(rotation));
    return Tensor<1, 3>({theta[0], theta[1], theta[2]});
  }

  namespace
  {
    /// I + b skew(theta) + c skew(theta)^2.
    Tensor<2, 3>
    polynomial_in_skew(const Tensor<1, 3> &theta, double b, double c)
    {
      const Tensor<2, 3> w      = skew(theta);
      Tensor<2, 3>       result = b * w + c * (w * w);
      for (unsigned int d = 0; d < 3; ++d)
        result[d][d] += 1;
      return result;
    }
  } // namespace

  Tensor<2, 3> so3_left_jacobian(const Tensor<1, 3> &theta)
  {
    const double t = theta.norm(), t2 = t * t;
    const double half_sine = std::sin(0.5 * t);
    // 1 - cos t as 2 sin^2(t/2) keeps its digits; t - sin t loses about
    // 6e-16 / t^2 of its own, so below 0.02 rad its series is used.
    const double b = t < 1e-8 ? 0.5 : 2 * half_sine * half_sine / t2;
    const double c = t < 0.02 ? 1.0 / 6 - t2 / 120 + t2 * t2 / 5040
                              : (t - std::sin(t)) / (t2 * t);
    return polynomial_in_skew(theta, b, c);
  }

  Tensor<2, 3> so3_left_jacobian_inverse(const Tensor<1, 3> &theta)
  {
    // (The form of c with 1 - cos t cost the SE(3) integrator a residual
    // floor of 3e-8; inverse_jacobian_coefficient keeps its digits.)
    const double c = inverse_jacobian_coefficient(theta.norm()).value;
    return polynomial_in_skew(theta, -0.5, c);
  }
} // namespace coshell::element
