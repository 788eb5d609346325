#include <coshell/base/parallel_environment.h>
#include <coshell/io/checkpoint.h>

#include "hdf5_reader.h"

#include <deal.II/base/hdf5.h>
#include <deal.II/lac/full_matrix.h>

#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace coshell::io
{
  using namespace dealii;

  namespace
  {
    /// Vectors are written only when filled (deal.II's wrappers make no
    /// empty datasets); attribute "has_NAME" says which are there.
    void write_vector(HDF5::File           &file,
                      const std::string    &name,
                      const Vector<double> &vector)
    {
      file.set_attribute("has_" + name, vector.size() > 0 ? 1u : 0u);
      if (vector.size() > 0)
        file.create_dataset<double>(name, {vector.size()}).write(vector);
    }

    void write_rotations(HDF5::File                      &file,
                         const std::vector<Tensor<2, 3>> &rotations)
    {
      FullMatrix<double> matrix(rotations.size(), 9);
      for (unsigned int v = 0; v < rotations.size(); ++v)
        for (unsigned int k = 0; k < 9; ++k)
          matrix(v, k) = rotations[v][k / 3][k % 3];
      file.create_dataset<double>("rotations", {rotations.size(), 9})
          .write(matrix);
    }

    /// Attribute "arrays" lists "name:size" of each; empty ones have no
    /// dataset.
    void write_arrays(HDF5::File                                       &file,
                      const std::map<std::string, std::vector<double>> &arrays)
    {
      std::string index;
      for (const auto &[name, values] : arrays)
      {
        index += (index.empty() ? "" : ",") + name + ":" +
                 std::to_string(values.size());
        if (!values.empty())
          file.create_dataset<double>(name, {values.size()}).write(values);
      }
      file.set_attribute("arrays", index);
    }
  } // namespace

  void write_checkpoint(const Checkpoint &checkpoint, const std::string &path)
  {
    // Every rank holds the same state; rank 0 writes it.
    if (!base::writes_output())
      return;
    const std::string partial = path + ".partial";
    {
      HDF5::File file(partial, HDF5::File::FileAccessMode::create);
      file.set_attribute("format", std::string(checkpoint_format));
      file.set_attribute("prm_file", checkpoint.prm_file);
      file.set_attribute("stage", checkpoint.stage);
      file.set_attribute("step", checkpoint.step);
      file.set_attribute("last_written", checkpoint.last_written);
      file.set_attribute("pvd_entries", checkpoint.pvd_entries);
      file.set_attribute("time", checkpoint.time);
      file.set_attribute("step_size", checkpoint.step_size);
      file.set_attribute("converged_force_scale",
                         checkpoint.converged_force_scale);
      file.set_attribute("external_work", checkpoint.external_work);
      file.set_attribute("dissipated_energy", checkpoint.dissipated_energy);
      file.set_attribute("body_frame_translations",
                         checkpoint.body_frame_translations ? 1u : 0u);
      write_vector(file, "values", checkpoint.values);
      write_vector(file, "velocity", checkpoint.velocity);
      write_vector(file, "acceleration", checkpoint.acceleration);
      write_vector(file, "pseudo_acceleration", checkpoint.pseudo_acceleration);
      write_vector(file, "generalized_force", checkpoint.generalized_force);
      write_vector(file, "damping_force", checkpoint.damping_force);
      write_rotations(file, checkpoint.rotations);
      write_arrays(file, checkpoint.arrays);
      file.set_attribute("has_csv_rows", checkpoint.csv_rows.empty() ? 0u : 1u);
      if (!checkpoint.csv_rows.empty())
        file.create_dataset<unsigned int>("csv_rows",
                                          {checkpoint.csv_rows.size()})
            .write(checkpoint.csv_rows);
    }
    std::filesystem::rename(partial, path);
  }

  namespace
  {
    Vector<double> read_vector(const Hdf5Reader  &file,
                               const std::string &name,
                               std::size_t        size)
    {
      if (file.attribute<unsigned int>("has_" + name) == 0)
        return {};
      const std::vector<double> values = file.dataset<double>(name);
      if (size != 0 && values.size() != size)
        throw std::invalid_argument(
            "dataset '" + name + "' has " + std::to_string(values.size()) +
            " entries, expected " + std::to_string(size));
      return Vector<double>(values.begin(), values.end());
    }

    std::vector<Tensor<2, 3>> read_rotations(const Hdf5Reader &file)
    {
      std::vector<unsigned int> shape;
      const auto matrix = file.dataset<double>("rotations", &shape);
      if (shape.size() != 2 || shape[1] != 9)
        throw std::invalid_argument("dataset 'rotations' must have 9 columns");
      std::vector<Tensor<2, 3>> rotations(shape[0]);
      for (unsigned int v = 0; v < shape[0]; ++v)
        for (unsigned int k = 0; k < 9; ++k)
          rotations[v][k / 3][k % 3] = matrix[9 * v + k];
      return rotations;
    }

    std::map<std::string, std::vector<double>>
    read_arrays(const Hdf5Reader &file)
    {
      std::map<std::string, std::vector<double>> arrays;
      std::istringstream index(file.string_attribute("arrays"));
      std::string        entry;
      while (std::getline(index, entry, ','))
      {
        const auto        colon = entry.rfind(':');
        const std::string name  = entry.substr(0, colon);
        arrays[name]            = {};
        if (std::stoul(entry.substr(colon + 1)) > 0)
          arrays[name] = file.dataset<double>(name);
      }
      return arrays;
    }

    /// The scalars and the names of the run's state.
    void read_scalars(const Hdf5Reader &file, Checkpoint &c)
    {
      if (file.string_attribute("format") != checkpoint_format)
        throw std::invalid_argument("not a CoShell checkpoint (attribute "
                                    "'format' is not '" +
                                    std::string(checkpoint_format) + "')");
      c.prm_file              = file.string_attribute("prm_file");
      c.stage                 = file.attribute<unsigned int>("stage");
      c.step                  = file.attribute<unsigned int>("step");
      c.last_written          = file.attribute<unsigned int>("last_written");
      c.pvd_entries           = file.attribute<unsigned int>("pvd_entries");
      c.time                  = file.attribute<double>("time");
      c.step_size             = file.attribute<double>("step_size");
      c.converged_force_scale = file.attribute<double>("converged_force_scale");
      c.external_work         = file.attribute<double>("external_work");
      c.dissipated_energy     = file.attribute<double>("dissipated_energy");
      c.body_frame_translations =
          file.attribute<unsigned int>("body_frame_translations") != 0;
    }

    Checkpoint read_fields(const Hdf5Reader &file)
    {
      Checkpoint c;
      read_scalars(file, c);
      c.values              = read_vector(file, "values", 0);
      const std::size_t n   = c.values.size();
      c.velocity            = read_vector(file, "velocity", n);
      c.acceleration        = read_vector(file, "acceleration", n);
      c.pseudo_acceleration = read_vector(file, "pseudo_acceleration", n);
      c.generalized_force   = read_vector(file, "generalized_force", n);
      c.damping_force       = read_vector(file, "damping_force", n);
      c.rotations           = read_rotations(file);
      c.arrays              = read_arrays(file);
      if (file.attribute<unsigned int>("has_csv_rows") != 0)
        c.csv_rows = file.dataset<unsigned int>("csv_rows");
      if (n == 0 || c.velocity.size() != n || !(c.step_size > 0))
        throw std::invalid_argument(
            "incomplete: it needs 'values', 'velocity' and a positive "
            "'step_size'");
      return c;
    }
  } // namespace

  namespace
  {
    /// What a checkpoint lacks, "" when complete: checked first, so that
    /// a foreign file is refused with all of it at once.
    std::string missing_parts(const Hdf5Reader &file)
    {
      if (!file.has_attribute("format"))
        return "attribute 'format'";
      if (!file.has_string_attribute("format"))
        return "attribute 'format' as a string";
      std::string missing;
      const auto  note = [&](const std::string &what)
      { missing += (missing.empty() ? "" : ", ") + what; };
      for (const char *name :
           {"prm_file", "stage", "step", "last_written", "pvd_entries", "time",
            "step_size", "converged_force_scale", "external_work",
            "dissipated_energy", "body_frame_translations", "has_values",
            "has_velocity", "has_acceleration", "has_pseudo_acceleration",
            "has_generalized_force", "has_damping_force", "has_csv_rows",
            "arrays"})
        if (!file.has_attribute(name))
          note(std::string("attribute '") + name + "'");
      for (const char *name :
           {"values", "velocity", "acceleration", "rotations"})
        if (!file.has_dataset(name))
          note(std::string("dataset '") + name + "'");
      return missing;
    }
  } // namespace

  Checkpoint read_checkpoint(const std::string &path)
  {
    const std::string where = "restart file '" + path + "': ";
    if (!std::filesystem::is_regular_file(path))
      throw std::invalid_argument(where + "no such file");
    // HDF5 prints its own error stack on failures; the message below says
    // it in one line instead.
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    if (H5Fis_hdf5(path.c_str()) <= 0)
      throw std::invalid_argument(where + "not an HDF5 file");
    try
    {
      const Hdf5Reader file(path);
      if (const std::string missing = missing_parts(file); !missing.empty())
        throw std::invalid_argument("not a CoShell checkpoint, it lacks " +
                                    missing);
      return read_fields(file);
    }
    catch (const std::invalid_argument &error)
    {
      throw std::invalid_argument(where + error.what());
    }
    catch (const std::exception &error) // a size out of range, say
    {
      throw std::invalid_argument(
          where + "not a readable CoShell checkpoint (" + error.what() + ")");
    }
  }
} // namespace coshell::io
