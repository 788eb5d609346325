#pragma once

#include <deal.II/base/data_out_base.h>
#include <deal.II/numerics/data_out.h>

#include <coshell/model/shell_model.h>

#include <deal.II/base/parameter_handler.h>

#include <map>
#include <string>
#include <vector>

namespace coshell::io
{
  /// VTU + PVD output of nodal displacement and rotation vectors and of
  /// per-cell membrane forces and bending moments (global-axis tensor
  /// components), from prm subsection "Output".
  class VtuOutput
  {
  public:
    /// A further nodal field in the DoF layout, one name per component
    /// (equal names form a vector).
    struct DofField
    {
      std::vector<std::string>      names;
      const dealii::Vector<double> *values = nullptr;
    };

    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm);

    /// Writes DIRECTORY/NAME.vtu and rewrites DIRECTORY/solution.pvd to
    /// list every file written to that directory so far, each at its
    /// 'time' (the load factor in nonlinear runs), so ParaView can step
    /// through them. 'companions' are other VTU files of the same instant
    /// in DIRECTORY (the obstacles), listed as further parts. Returns the
    /// .pvd path, or "" when output is off.
    std::string write(const model::ShellModel                     &model,
                      const dealii::Vector<double>                &values,
                      const std::vector<element::ShellResultants> &resultants,
                      const std::string                           &directory,
                      const std::string              &name       = "solution",
                      double                          time       = 0,
                      const std::vector<DofField>    &fields     = {},
                      const std::vector<std::string> &companions = {});

    /// Whether nonlinear step 'step' should be written (the last step is
    /// always written by the caller). A step that ends a dynamic stage is
    /// written unless only the run's last one is asked for: each stage's
    /// end state is in the series, whatever the stride.
    bool wants_step(unsigned int step, bool ends_stage = false) const;
    bool writes_vtu() const
    {
      return write_vtu_;
    }

    /// Entries of DIRECTORY's series so far (files and their companions).
    unsigned int series_size(const std::string &directory) const;
    /// Starts DIRECTORY's series with the first 'entries' entries of an
    /// earlier run's .pvd (a restart). Returns false, leaving the series
    /// empty, when that file is missing or shorter.
    bool resume_series(const std::string &directory,
                       const std::string &earlier_pvd,
                       unsigned int       entries);

    /// Output directory from the prm ("Output/Directory").
    std::string directory = "output";

  private:
    bool write_vtu_ = true;
    /// Output/Vertex table: NAME.vertices.csv in double precision.
    bool vertex_table_ = false;
    void write_vertex_table(const model::ShellModel      &model,
                            const dealii::Vector<double> &solution,
                            const std::string            &path);
    /// Output/Format: VTU files and solution.pvd, or HDF5 files (duplicate
    /// vertices filtered) and solution.xdmf.
    bool hdf5_ = false;
    /// Output/Format = pvtu: one piece per rank and NAME.pvtu.
    bool                                                  pvtu_ = false;
    std::map<std::string, std::vector<dealii::XDMFEntry>> xdmf_series_;

    /// Adds a step (and its companion files) to the series of 'directory';
    /// returns the series file. Ranks other than 0 only keep the count.
    std::string record_series(const std::string              &directory,
                              const std::string              &name,
                              double                          time,
                              const std::vector<std::string> &companions);
    /// Displacement, rotation, the extra DoF fields, N, M, material id,
    /// thickness and the cells' strains.
    void add_fields(dealii::DataOut<2, 3>                       &data_out,
                    const model::ShellModel                     &model,
                    const dealii::Vector<double>                &solution,
                    const std::vector<element::ShellResultants> &resultants,
                    const std::vector<DofField>                 &fields) const;
    /// This rank's NAME.piece-RANK.vtu and, on rank 0, NAME.pvtu.
    void         write_pieces(const dealii::DataOut<2, 3> &data_out,
                              const std::string           &directory,
                              const std::string           &name) const;
    std::string  write_hdf5(const dealii::DataOut<2, 3> &data_out,
                            const std::string           &output_directory,
                            const std::string           &name,
                            double                       time);
    unsigned int steps_between_output_ = 1;
    struct Entry
    {
      double       time;
      unsigned int part;
      std::string  file;
    };
    std::map<std::string, std::vector<Entry>> series_;
    static void                               write_pvd(const std::string        &pvd,
                                                        const std::vector<Entry> &series);
  };
} // namespace coshell::io
