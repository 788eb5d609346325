#include <coshell/element/shell_element.h>

#include <algorithm>

namespace coshell::element
{
  namespace
  {
    using Components = std::array<unsigned int, 3>;

    // Where the 3 DOFs per node of each sub-element sit among the 6 local
    // DOFs (u, v, w, theta_x, theta_y, theta_z) of a node.
    constexpr Components membrane_components = {{0, 1, 5}};
    constexpr Components bending_components  = {{2, 3, 4}};

    constexpr unsigned int shell_dof(unsigned int      sub_dof,
                                     const Components &components)
    {
      return 6 * (sub_dof / 3) + components[sub_dof % 3];
    }

    void add_sub_element(const FullMatrix<double> &sub_stiffness,
                         const Components         &components,
                         FullMatrix<double>       &shell)
    {
      for (unsigned int a = 0; a < 9; ++a)
        for (unsigned int b = 0; b < 9; ++b)
          shell(shell_dof(a, components), shell_dof(b, components)) +=
              sub_stiffness(a, b);
    }

    std::array<double, 9> sub_element_dofs(const ShellDisplacements &local,
                                           const Components         &components)
    {
      std::array<double, 9> dofs;
      for (unsigned int a = 0; a < 9; ++a)
        dofs[a] = local[shell_dof(a, components)];
      return dofs;
    }

    // sum_ab R_ab e_a (x) e_b over the in-plane axes, R = [[xx, xy], [xy, yy]].
    Tensor<2, 3> to_global_tensor(const ElementFrame          &frame,
                                  const std::array<double, 3> &resultant)
    {
      const double components[2][2] = {{resultant[0], resultant[2]},
                                       {resultant[2], resultant[1]}};
      Tensor<2, 3> global;
      for (unsigned int a = 0; a < 2; ++a)
        for (unsigned int b = 0; b < 2; ++b)
          global += components[a][b] *
                    dealii::outer_product(frame.axes[a], frame.axes[b]);
      return global;
    }

    // The CST has no stiffness of its own on theta_z and gets the drilling
    // penalty; ANDES resists theta_z itself, so a penalty would only
    // stiffen it.
    FullMatrix<double> membrane_stiffness(const PlanarTriangle      &triangle,
                                          const ShellMaterial       &material,
                                          const ShellElementOptions &options)
    {
      if (*options.membrane == MembraneElement::andes)
        return andes_stiffness(triangle, material, options.andes_scales);
      FullMatrix<double> membrane = options.membrane_in_plane
                                        ? cst_stiffness(triangle, material)
                                        : FullMatrix<double>(9, 9);
      add_drilling_penalty(triangle, material, options.drilling_factor,
                           membrane);
      return membrane;
    }

    MembraneForces membrane_forces(const ShellElementOptions   &options,
                                   const PlanarTriangle        &triangle,
                                   const ShellMaterial         &material,
                                   const MembraneDisplacements &dofs)
    {
      if (*options.membrane == MembraneElement::andes)
        return andes_membrane_forces(triangle, material, dofs,
                                     options.andes_scales);
      if (!options.membrane_in_plane)
        return {};
      return cst_membrane_forces(triangle, material, dofs);
    }
  } // namespace

  FullMatrix<double> shell_stiffness_local(const ElementFrame        &frame,
                                           const ShellMaterial       &material,
                                           const ShellElementOptions &options)
  {
    material.validate();
    FullMatrix<double> local(shell_dofs, shell_dofs);
    if (options.membrane)
      add_sub_element(membrane_stiffness(frame.planar, material, options),
                      membrane_components, local);
    if (options.bending)
      add_sub_element(
          bending_stiffness(*options.bending, frame.planar, material),
          bending_components, local);
    return local;
  }

  FullMatrix<double> shell_stiffness(const SpatialTriangle     &triangle,
                                     const ShellMaterial       &material,
                                     const ShellElementOptions &options)
  {
    material.validate(); // before the geometry check: a bad material is
                         // reported first
    const ElementFrame frame = make_element_frame(triangle);
    return rotate_to_global(shell_stiffness_local(frame, material, options),
                            frame.axes);
  }

  FullMatrix<double> rotate_to_global(const FullMatrix<double>          &local,
                                      const std::array<Tensor<1, 3>, 3> &axes)
  {
    FullMatrix<double> global;
    rotate_to_global(local, axes, global);
    return global;
  }

  void rotate_to_global(const FullMatrix<double>          &local,
                        const std::array<Tensor<1, 3>, 3> &axes,
                        FullMatrix<double>                &global)
  {
    // T = diag(R, ..., R) with R_ab = (e_a)_b, so each 3x3 block transforms
    // on its own: K_IJ = R^T K_local,IJ R. Block by block this costs 36 x 54
    // multiply-adds instead of the dense 2 x 18^3.
    constexpr unsigned int blocks = shell_dofs / 3;
    if (global.m() != shell_dofs || global.n() != shell_dofs)
      global.reinit(shell_dofs, shell_dofs);
    for (unsigned int bi = 0; bi < blocks; ++bi)
      for (unsigned int bj = 0; bj < blocks; ++bj)
      {
        double right[3][3] = {}; // K_local,IJ R
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int b = 0; b < 3; ++b)
            for (unsigned int c = 0; c < 3; ++c)
              right[a][c] += local(3 * bi + a, 3 * bj + b) * axes[b][c];
        for (unsigned int r = 0; r < 3; ++r)
          for (unsigned int c = 0; c < 3; ++c)
          {
            double sum = 0;
            for (unsigned int a = 0; a < 3; ++a)
              sum += axes[a][r] * right[a][c];
            global(3 * bi + r, 3 * bj + c) = sum;
          }
      }
  }

  ShellDisplacements to_element_frame(const ElementFrame       &frame,
                                      const ShellDisplacements &global_dofs)
  {
    ShellDisplacements local;
    for (unsigned int block = 0; block < 6; ++block)
    {
      Tensor<1, 3> vector;
      for (unsigned int a = 0; a < 3; ++a)
        vector[a] = global_dofs[3 * block + a];
      const Tensor<1, 3> rotated = to_local(frame, vector);
      for (unsigned int a = 0; a < 3; ++a)
        local[3 * block + a] = rotated[a];
    }
    return local;
  }

  namespace
  {
    /// The membrane forces and bending moments of element-frame DOFs.
    ShellResultants local_resultants(const PlanarTriangle      &planar,
                                     const ShellMaterial       &material,
                                     const ShellElementOptions &options,
                                     const ShellDisplacements  &local)
    {
      ShellResultants result;
      if (options.membrane)
        result.membrane_local =
            membrane_forces(options, planar, material,
                            sub_element_dofs(local, membrane_components));
      if (options.bending)
        result.bending_local =
            bending_moments(*options.bending, planar, material,
                            sub_element_dofs(local, bending_components));
      return result;
    }

    void set_global_tensors(const ElementFrame &frame, ShellResultants &result)
    {
      result.membrane_global = to_global_tensor(frame, result.membrane_local);
      result.bending_global  = to_global_tensor(frame, result.bending_local);
    }
  } // namespace

  ShellResultants shell_resultants(const SpatialTriangle     &triangle,
                                   const ShellMaterial       &material,
                                   const ShellElementOptions &options,
                                   const ShellDisplacements  &dofs)
  {
    const ElementFrame frame = make_element_frame(triangle);
    ShellResultants result   = local_resultants(frame.planar, material, options,
                                                to_element_frame(frame, dofs));
    set_global_tensors(frame, result);
    return result;
  }

  ResultantRecovery::ResultantRecovery(const PlanarTriangle      &planar,
                                       const ShellMaterial       &material,
                                       const ShellElementOptions &options)
  {
    // Both resultants are linear in the DOFs: column j is the response to
    // the j-th unit DOF.
    for (unsigned int j = 0; j < shell_dofs; ++j)
    {
      ShellDisplacements unit{};
      unit[j] = 1;
      const ShellResultants r =
          local_resultants(planar, material, options, unit);
      for (unsigned int k = 0; k < 3; ++k)
      {
        map_[k][j]     = r.membrane_local[k];
        map_[3 + k][j] = r.bending_local[k];
      }
    }
  }

  ShellResultants
  ResultantRecovery::resultants(const std::array<Tensor<1, 3>, 3> &axes,
                                const ShellDisplacements          &local) const
  {
    ShellResultants result;
    for (unsigned int k = 0; k < 3; ++k)
      for (unsigned int j = 0; j < shell_dofs; ++j)
      {
        result.membrane_local[k] += map_[k][j] * local[j];
        result.bending_local[k] += map_[3 + k][j] * local[j];
      }
    ElementFrame frame;
    frame.axes = axes;
    set_global_tensors(frame, result);
    return result;
  }
} // namespace coshell::element
