#include <coshell/base/parallel_environment.h>
#include <coshell/io/json.h>
#include <coshell/io/vtu_output.h>
#include <coshell/model/internal_force.h>

#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/grid/filtered_iterator.h>
#include <deal.II/numerics/data_out.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace coshell::io
{
  using namespace dealii;

  void VtuOutput::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.declare_entry("Directory", "output", Patterns::Anything(),
                      "Directory path where results go (the command "
                      "line's --output wins).");
    prm.declare_entry("Write VTU", "true", Patterns::Bool(),
                      "Selects whether to write the fields for ParaView "
                      "(true/false): solution.vtu and solution.pvd, or with "
                      "Format = hdf5 solution.h5 and solution.xdmf.");
    prm.declare_entry(
        "Format", "vtu", Patterns::Selection("vtu|pvtu|hdf5"),
        "vtu: one NAME.vtu per output and solution.pvd listing them; pvtu: "
        "under mpirun each rank writes the triangles it owns to "
        "NAME.piece-RANK.vtu and rank 0 writes NAME.pvtu joining them "
        "(one piece on one rank), listed in solution.pvd; hdf5: "
        "one NAME.h5 (mesh with duplicate vertices merged, and the fields) "
        "per output and solution.xdmf listing them with their times. "
        "ParaView opens both (the .xdmf with its Xdmf reader). Cell fields "
        "(N, M, material_id, thickness) become values at the merged "
        "vertices, taken from one of the triangles around each. Obstacles "
        "of contact scenes are VTU files either way, and a restart's "
        ".xdmf lists only its own steps.");
    prm.declare_entry(
        "Vertex table", "false", Patterns::Bool(),
        "Selects whether each field output also writes NAME.vertices.csv: "
        "per mesh vertex its reference position (length unit) and its six "
        "unknowns (displacement in the length unit, rotation vector in "
        "rad) with 17 significant digits. VTU and HDF5 fields are rounded "
        "to single precision by deal.II; this table is not (true/false).");
    prm.declare_entry("Steps between outputs", "1", Patterns::Integer(0),
                      "Nonlinear runs: write every n-th converged load step "
                      "and, in dynamic stages, each stage's last step (0: "
                      "only the run's last one). Unit: dimensionless (a "
                      "step count).");
    prm.leave_subsection();
  }

  void VtuOutput::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    directory             = prm.get("Directory");
    write_vtu_            = prm.get_bool("Write VTU");
    hdf5_                 = prm.get("Format") == "hdf5";
    pvtu_                 = prm.get("Format") == "pvtu";
    vertex_table_         = prm.get_bool("Vertex table");
    steps_between_output_ = prm.get_integer("Steps between outputs");
    prm.leave_subsection();
  }

  namespace
  {
    /// One cell-data field per independent tensor component. DataOut
    /// copies each vector as it is added (deal.II 9.4's DataEntry), so the
    /// fields may be temporaries.
    void add_tensor_fields(DataOut<2, 3>                   &data_out,
                           const std::vector<Tensor<2, 3>> &tensors,
                           const std::string               &symbol)
    {
      static const std::array<std::pair<unsigned int, unsigned int>, 6>
          entries = {{{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}}};
      static const std::array<std::string, 6> suffix = {
          {"xx", "yy", "zz", "xy", "yz", "xz"}};
      for (unsigned int e = 0; e < entries.size(); ++e)
      {
        Vector<double> field(tensors.size());
        for (unsigned int c = 0; c < tensors.size(); ++c)
          field[c] = tensors[c][entries[e].first][entries[e].second];
        data_out.add_data_vector(field, symbol + "_" + suffix[e],
                                 DataOut<2, 3>::type_cell_data);
      }
    }

    /// Per cell: material id, thickness and the largest principal
    /// membrane, bending and surface strains (model::cell_strains).
    void
    add_cell_scalars(DataOut<2, 3>                               &data_out,
                     const model::ShellModel                     &model,
                     const std::vector<element::ShellResultants> &resultants)
    {
      static const std::array<std::string, 5> names = {
          {"material_id", "thickness", "membrane_strain", "bending_strain",
           "surface_strain"}};
      std::array<Vector<double>, 5> fields;
      for (auto &field : fields)
        field.reinit(model.surface().n_active_cells());
      for (const auto &cell : model.dof_handler().active_cell_iterators())
      {
        const unsigned int c        = cell->active_cell_index();
        const auto        &material = model.material(cell);
        const auto strains = model::cell_strains(material, resultants[c]);
        fields[0][c]       = cell->material_id();
        fields[1][c]       = material.thickness;
        fields[2][c]       = strains.membrane;
        fields[3][c]       = strains.bending;
        fields[4][c]       = strains.surface;
      }
      for (unsigned int f = 0; f < fields.size(); ++f)
        data_out.add_data_vector(fields[f], names[f],
                                 DataOut<2, 3>::type_cell_data);
    }
  } // namespace

  void VtuOutput::write_vertex_table(const model::ShellModel &model,
                                     const Vector<double>    &solution,
                                     const std::string       &path)
  {
    std::ostringstream table;
    table << "vertex,x,y,z,ux,uy,uz,rx,ry,rz\n" << std::setprecision(17);
    const auto &vertices = model.surface().get_vertices();
    for (unsigned int v = 0; v < vertices.size(); ++v)
    {
      if (!model.vertex_is_used(v))
        continue;
      table << v;
      for (unsigned int d = 0; d < 3; ++d)
        table << ',' << vertices[v][d];
      for (const auto dof : model.vertex_dofs(v))
        table << ',' << solution[dof];
      table << '\n';
    }
    std::filesystem::create_directories(
        std::filesystem::path(path).parent_path());
    write_file_atomically(path, table.str());
  }

  bool VtuOutput::wants_step(unsigned int step, bool ends_stage) const
  {
    return write_vtu_ && steps_between_output_ > 0 &&
           (ends_stage || step % steps_between_output_ == 0);
  }

  void
  VtuOutput::add_fields(DataOut<2, 3>                               &data_out,
                        const model::ShellModel                     &model,
                        const Vector<double>                        &solution,
                        const std::vector<element::ShellResultants> &resultants,
                        const std::vector<DofField> &fields) const
  {
    std::vector<std::string> names(3, "displacement");
    names.insert(names.end(), 3, "rotation");
    // DataOut knows the FESystem's DoFs only; the thickness stretches
    // enter as the cells' current thickness.
    data_out.add_data_vector(
        model.fe_part(solution), names, DataOut<2, 3>::type_dof_data,
        std::vector<DataComponentInterpretation::DataComponentInterpretation>(
            6, DataComponentInterpretation::component_is_part_of_vector));
    for (const DofField &field : fields)
    {
      std::vector<DataComponentInterpretation::DataComponentInterpretation>
          kinds;
      for (const auto &component : field.names)
        kinds.push_back(
            std::count(field.names.begin(), field.names.end(), component) > 1
                ? DataComponentInterpretation::component_is_part_of_vector
                : DataComponentInterpretation::component_is_scalar);
      data_out.add_data_vector(model.fe_part(*field.values), field.names,
                               DataOut<2, 3>::type_dof_data, kinds);
    }
    std::vector<Tensor<2, 3>> membrane, bending;
    for (const auto &r : resultants)
    {
      membrane.push_back(r.membrane_global);
      bending.push_back(r.bending_global);
    }
    add_tensor_fields(data_out, membrane, "N");
    add_tensor_fields(data_out, bending, "M");
    add_cell_scalars(data_out, model, resultants);
    if (model.has_thickness_stretch())
    {
      Vector<double> thickness(model.surface().n_active_cells());
      for (const auto &cell : model.dof_handler().active_cell_iterators())
        thickness[cell->active_cell_index()] =
            model.current_thickness(cell, solution);
      data_out.add_data_vector(thickness, "current_thickness",
                               DataOut<2, 3>::type_cell_data);
    }
  }

  std::string
  VtuOutput::write(const model::ShellModel                     &model,
                   const Vector<double>                        &solution,
                   const std::vector<element::ShellResultants> &resultants,
                   const std::string              &output_directory,
                   const std::string              &name,
                   double                          time,
                   const std::vector<DofField>    &fields,
                   const std::vector<std::string> &companions)
  {
    if (!write_vtu_)
      return "";
    // With pvtu every rank writes the piece of its own cells.
    if (!base::writes_output() && !pvtu_)
      return record_series(output_directory, name, time, companions);
    if (vertex_table_ && base::writes_output())
      write_vertex_table(model, solution,
                         output_directory + "/" + name + ".vertices.csv");
    DataOut<2, 3> data_out;
    data_out.attach_dof_handler(model.dof_handler());
    add_fields(data_out, model, solution, resultants, fields);
    if (pvtu_)
    {
      const unsigned int rank = base::this_rank();
      data_out.set_cell_selection(
          FilteredIterator<Triangulation<2, 3>::cell_iterator>(
              [rank](const Triangulation<2, 3>::cell_iterator &cell)
              { return cell->is_active() && cell->subdomain_id() == rank; }));
    }
    const MappingFE<2, 3> mapping(FE_SimplexP<2, 3>(1));
    data_out.build_patches(mapping);
    std::filesystem::create_directories(output_directory);
    if (hdf5_)
      return write_hdf5(data_out, output_directory, name, time);
    if (pvtu_)
      write_pieces(data_out, output_directory, name);
    else
    {
      std::ofstream out(output_directory + "/" + name + ".vtu");
      data_out.write_vtu(out);
    }
    const std::string pvd =
        record_series(output_directory, name, time, companions);
    if (base::writes_output())
      write_pvd(pvd, series_[output_directory]);
    return pvd;
  }

  void VtuOutput::write_pieces(const DataOut<2, 3> &data_out,
                               const std::string   &directory,
                               const std::string   &name) const
  {
    const auto piece = [&](unsigned int rank)
    { return name + ".piece-" + std::to_string(rank) + ".vtu"; };
    {
      std::ofstream out(directory + "/" + piece(base::this_rank()));
      data_out.write_vtu(out);
    }
    if (base::writes_output())
    {
      std::vector<std::string> pieces;
      for (unsigned int rank = 0; rank < base::n_ranks(); ++rank)
        pieces.push_back(piece(rank));
      std::ofstream out(directory + "/" + name + ".pvtu");
      data_out.write_pvtu_record(out, pieces);
    }
  }

  void VtuOutput::write_pvd(const std::string        &pvd,
                            const std::vector<Entry> &series)
  {
    std::ofstream out(pvd);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" "
           "version=\"0.1\">\n<Collection>\n";
    for (const Entry &entry : series)
      out << "<DataSet timestep=\"" << std::setprecision(12) << entry.time
          << "\" group=\"\" part=\"" << entry.part << "\" file=\"" << entry.file
          << "\"/>\n";
    out << "</Collection>\n</VTKFile>\n";
  }

  std::string VtuOutput::write_hdf5(const DataOut<2, 3> &data_out,
                                    const std::string   &output_directory,
                                    const std::string   &name,
                                    double               time)
  {
    // deal.II writes HDF5 through MPI-IO; a serial run starts MPI here.
    base::ensure_mpi_initialized();
    DataOutBase::DataOutFilter filter(
        DataOutBase::DataOutFilterFlags(true, true));
    data_out.write_filtered_data(filter);
    const std::string h5 = name + ".h5";
    data_out.write_hdf5_parallel(filter, output_directory + "/" + h5,
                                 MPI_COMM_SELF);
    auto &series = xdmf_series_[output_directory];
    series.push_back(
        data_out.create_xdmf_entry(filter, h5, time, MPI_COMM_SELF));
    const std::string xdmf = output_directory + "/solution.xdmf";
    data_out.write_xdmf_file(series, xdmf, MPI_COMM_SELF);
    return xdmf;
  }

  std::string
  VtuOutput::record_series(const std::string              &directory,
                           const std::string              &name,
                           double                          time,
                           const std::vector<std::string> &companions)
  {
    if (hdf5_)
      return directory + "/solution.xdmf";
    auto &series = series_[directory];
    series.push_back({time, 0, name + (pvtu_ ? ".pvtu" : ".vtu")});
    for (unsigned int k = 0; k < companions.size(); ++k)
      series.push_back({time, k + 1, companions[k]});
    return directory + "/solution.pvd";
  }

  unsigned int VtuOutput::series_size(const std::string &directory) const
  {
    const auto found = series_.find(directory);
    return found == series_.end() ? 0 : found->second.size();
  }

  namespace
  {
    /// The value of 'key="..."' in a line of our .pvd files, or "".
    std::string xml_attribute(const std::string &line, const std::string &key)
    {
      const std::string marker = key + "=\"";
      const auto        start  = line.find(marker);
      if (start == std::string::npos)
        return "";
      const auto end = line.find('"', start + marker.size());
      return line.substr(start + marker.size(), end - start - marker.size());
    }
  } // namespace

  bool VtuOutput::resume_series(const std::string &directory,
                                const std::string &earlier_pvd,
                                unsigned int       entries)
  {
    std::vector<Entry> series;
    std::ifstream      in(earlier_pvd);
    std::string        line;
    while (series.size() < entries && std::getline(in, line))
      if (line.rfind("<DataSet ", 0) == 0)
        series.push_back(
            {std::stod(xml_attribute(line, "timestep")),
             static_cast<unsigned int>(std::stoul(xml_attribute(line, "part"))),
             xml_attribute(line, "file")});
    if (series.size() < entries)
      return false;
    series_[directory] = series;
    return true;
  }
} // namespace coshell::io
