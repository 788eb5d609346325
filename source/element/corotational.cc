// Co-rotational shell triangle (EICR, Rankin & Nour-Omid 1988; Felippa &
// Haugen 2005). The kinematic map p -> d (perturbation of the current state
// -> deformational DOFs) is differentiated with Sacado forward AD; the
// material part stays the linear 1/2 d^T K_l d, contracted in double.
//
// The map is split to keep the AD cheap. The co-rotated frame E and the
// in-plane deformational translations depend on the 9 vertex translations u
// only. Writing a perturbed frame as E(u) = exp(skew(omega(u))) E, the
// deformational rotation of node i,
//   theta_d,i = axial log(E(u)^T exp(skew(theta_i)) R_i E0),
// depends on u only through the spin omega(u), so it is differentiated with
// respect to the 6 variables (omega, theta_i) and chained with the
// derivatives of omega(u).

#include <coshell/element/corotational.h>

#include <deal.II/lac/vector.h>

#include <Sacado.hpp>

#include <cmath>
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

    template<typename T>
    Mat3<double> values_of(const Mat3<T> &a)
    {
      Mat3<double> v;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          v[i][j] = value_of(a[i][j]);
      return v;
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

    // Spin omega with E(u) = exp(skew(omega)) E(0), to second order in u:
    // with D = E(u) E(0)^T - I = O(u), log(I + D) = D - D^2/2 + O(u^3).
    template<typename T>
    Vec3<T> frame_spin(const Mat3<T> &axes, const Mat3<double> &axes_at_zero)
    {
      Mat3<T> d;
      for (unsigned int r = 0; r < 3; ++r)
        for (unsigned int s = 0; s < 3; ++s)
          d[r][s] = axes[0][r] * axes_at_zero[0][s] +
                    axes[1][r] * axes_at_zero[1][s] +
                    axes[2][r] * axes_at_zero[2][s] - (r == s ? 1.0 : 0.0);
      const Mat3<T> d_squared = product(d, d);
      Vec3<T>       spin;
      for (unsigned int i = 0; i < 3; ++i)
      {
        const unsigned int j = (i + 1) % 3, k = (i + 2) % 3;
        spin[i] = 0.5 * ((d[k][j] - d[j][k]) -
                         0.5 * (d_squared[k][j] - d_squared[j][k]));
      }
      return spin;
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

    /// Forward AD of order 1 (gradient) or 2 (gradient and Hessian) in n
    /// variables; order 0 is plain evaluation.
    template<int order, int n>
    struct Jet;

    template<int n>
    struct Jet<0, n>
    {
      using type = double;
      static type variable(double value, int)
      {
        return value;
      }
    };

    template<int n>
    struct Jet<1, n>
    {
      using type = Sacado::Fad::SFad<double, n>;
      static type variable(double value, int k)
      {
        return type(n, k, value);
      }
      static double derivative(const type &x, int k)
      {
        return x.dx(k);
      }
    };

    template<int n>
    struct Jet<2, n>
    {
      using inner = Sacado::Fad::SFad<double, n>;
      using type  = Sacado::Fad::SFad<inner, n>;
      static type variable(double value, int k)
      {
        return type(n, k, inner(n, k, value));
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

    // The translations and the frame depend on the vertices only through
    // the edges e1 = x1 - x0 and e2 = x2 - x0 (a rigid translation moves
    // neither), so the AD runs in those 6 variables (3 * edge + component):
    // d/dx_v = sum_e edge_weight[v][e] d/de_e.
    constexpr double edge_weight[3][2] = {{-1.0, -1.0}, {1.0, 0.0}, {0.0, 1.0}};

    void require_nondegenerate(const SpatialTriangle &current)
    {
      make_element_frame(current); // throws DegenerateTriangle
    }

    // d and its derivatives with respect to the perturbation p at p = 0:
    // the edges (6 AD variables) drive the frame and the in-plane
    // translations; each node's rotation is differentiated in closed form
    // with respect to (omega, theta_i) and chained with the derivatives of
    // omega(u). Order 0 gives d alone.
    template<int order>
    class CorotatedKinematics
    {
    public:
      CorotatedKinematics(const CorotationalReference &reference,
                          const SpatialTriangle       &current,
                          const NodalRotations        &rotations)
      {
        require_nondegenerate(current);
        std::array<Vec3<Translational>, 3> x;
        for (unsigned int c = 0; c < 3; ++c)
        {
          x[0][c] = current[0][c];
          x[1][c] = TranslationJet::variable(current[1][c], c);
          x[2][c] = TranslationJet::variable(current[2][c], 3 + c);
        }
        const CorotatedConfiguration<Translational> configuration =
            corotate(reference, x);
        translations = configuration.translations;
        axes         = values_of(configuration.axes);
        if constexpr (order > 0)
          spin = frame_spin(configuration.axes, axes);

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
              d[6 * i + c] = value_of(translations[i][c]);
            d[rotation_dof(i, c)] = nodal_rotations[i].value[c];
          }
        return d;
      }

      /// J = dd/dp (18 x 18); the rows of w are zero.
      void jacobian(Matrix18 &j) const
      {
        j = {};
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int c = 0; c < 2; ++c)
          {
            const auto gradient = vertex_gradient(translations[i][c]);
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
        std::array<std::array<double, 6>, 6> edge_hessian{};
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int c = 0; c < 2; ++c)
            add_edge_hessian(weights[6 * i + c], translations[i][c],
                             edge_hessian);
        const auto spin_gradient = spin_vertex_gradient();
        for (unsigned int i = 0; i < 3; ++i)
          add_rotation_hessian(i, weights, spin_gradient, edge_hessian, h);

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
      using TranslationJet = Jet<order, 6>;
      using Translational  = typename TranslationJet::type;
      using SpinGradient   = std::array<std::array<double, 9>, 3>;

      static std::array<double, 9> vertex_gradient(const Translational &x)
      {
        std::array<double, 9> gradient;
        for (unsigned int c = 0; c < 3; ++c)
        {
          const double d1 = TranslationJet::derivative(x, c);
          const double d2 = TranslationJet::derivative(x, 3 + c);
          gradient[c]     = -d1 - d2;
          gradient[3 + c] = d1;
          gradient[6 + c] = d2;
        }
        return gradient;
      }

      /// Omega = d omega / du (3 x 9).
      SpinGradient spin_vertex_gradient() const
      {
        SpinGradient gradient;
        for (unsigned int m = 0; m < 3; ++m)
          gradient[m] = vertex_gradient(spin[m]);
        return gradient;
      }

      static void add_edge_hessian(double                                weight,
                                   const Translational                  &x,
                                   std::array<std::array<double, 6>, 6> &h)
      {
        for (unsigned int a = 0; a < 6; ++a)
          for (unsigned int b = 0; b < 6; ++b)
            h[a][b] += weight * TranslationJet::second_derivative(x, a, b);
      }

      // Chain rule through omega(u) for psi = sum_a w_a theta_d,a(omega,
      // theta): psi_uu = Omega^T psi_ww Omega + psi_w . omega_uu, psi_ut =
      // Omega^T psi_wt, with Omega = d omega / du. The omega_uu term is
      // gathered in the edge variables.
      void add_rotation_hessian(unsigned int                          i,
                                const ShellDisplacements             &weights,
                                const SpinGradient                   &omega,
                                std::array<std::array<double, 6>, 6> &edge_h,
                                Matrix18                             &h) const
      {
        const Vec3<double>              w = {{weights[rotation_dof(i, 0)],
                                              weights[rotation_dof(i, 1)],
                                              weights[rotation_dof(i, 2)]}};
        const NodalRotationDerivatives &rotation = nodal_rotations[i];
        const auto psi_hessian = rotation_hessian(rotation, axes, w);
        // d psi / d omega = -M A.
        const Vec3<double> psi_spin =
            scaled(-1.0, transpose_times(rotation.gradient, w));
        for (unsigned int m = 0; m < 3; ++m)
          add_edge_hessian(psi_spin[m], spin[m], edge_h);

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

      std::array<std::array<Translational, 2>, 3> translations{};
      Vec3<Translational>                         spin{}; ///< order > 0
      std::array<NodalRotationDerivatives, 3>     nodal_rotations{};
      Mat3<double>                                axes{};
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
      : reference(make_reference(initial)), material(material),
        options(options),
        stiffness(shell_stiffness_local(reference.frame, material, options))
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
      const Mat3<double>         &e = jets.frame();
      std::array<Tensor<1, 3>, 3> axes;
      for (unsigned int a = 0; a < 3; ++a)
        axes[a] = Tensor<1, 3>({e[a][0], e[a][1], e[a][2]});
      *tangent = rotate_to_global(stiffness, axes);
    }
  }

  ShellResultants
  CorotationalShell::resultants(const SpatialTriangle &current,
                                const NodalRotations  &rotations) const
  {
    // The initial shape carried rigidly onto the current frame has that
    // frame as its element frame and the initial planar coordinates, so
    // the linear resultants apply to it with d rotated to global axes.
    const CorotatedKinematics<0> state(reference, current, rotations);
    const Mat3<double>          &axes = state.frame();
    const ShellDisplacements     d    = state.dofs();
    const Point<3> centroid((current[0] + current[1] + current[2]) / 3.0);
    const auto     to_global = [&](double a, double b, double c)
    {
      Tensor<1, 3> v;
      for (unsigned int r = 0; r < 3; ++r)
        v[r] = a * axes[0][r] + b * axes[1][r] + c * axes[2][r];
      return v;
    };

    SpatialTriangle    carried;
    ShellDisplacements global;
    for (unsigned int i = 0; i < 3; ++i)
      carried[i] = centroid + to_global(reference.coordinates[i][0],
                                        reference.coordinates[i][1], 0.0);
    for (unsigned int block = 0; block < 6; ++block)
    {
      const Tensor<1, 3> v =
          to_global(d[3 * block], d[3 * block + 1], d[3 * block + 2]);
      for (unsigned int r = 0; r < 3; ++r)
        global[3 * block + r] = v[r];
    }
    return shell_resultants(carried, material, options, global);
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
