#pragma once

#include <hdf5.h>

#include <string>
#include <vector>

namespace coshell::io
{
  /// An HDF5 file opened read-only, through HDF5's C interface, with every
  /// read checked. deal.II 9.4's HDF5::File opens an existing file for
  /// writing: a checkpoint that another run has open (HDF5 locks it) or
  /// that is read-only fails to open there, and its reads, unchecked in
  /// release builds, then crashed (two haptic runs restarting from one
  /// fold). Every failure throws std::invalid_argument naming the part.
  class Hdf5Reader
  {
  public:
    explicit Hdf5Reader(const std::string &path);
    ~Hdf5Reader();
    Hdf5Reader(const Hdf5Reader &)            = delete;
    Hdf5Reader &operator=(const Hdf5Reader &) = delete;

    bool has_attribute(const std::string &name) const;
    bool has_dataset(const std::string &name) const;
    /// Whether attribute 'name' is a variable-length string (the kind
    /// deal.II writes).
    bool has_string_attribute(const std::string &name) const;

    /// A scalar attribute, converted to T (unsigned int or double).
    template<typename T>
    T           attribute(const std::string &name) const;
    std::string string_attribute(const std::string &name) const;

    /// The dataset's entries in HDF5's (row-major) order, converted to T
    /// (unsigned int or double); 'dimensions' receives its shape if given.
    template<typename T>
    std::vector<T>
    dataset(const std::string         &name,
            std::vector<unsigned int> *dimensions = nullptr) const;

  private:
    hid_t file_;
  };
} // namespace coshell::io
