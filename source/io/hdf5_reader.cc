#include "hdf5_reader.h"

#include <memory>
#include <stdexcept>
#include <type_traits>

namespace coshell::io
{
  namespace
  {
    /// Closes an HDF5 identifier when it goes out of scope.
    class Handle
    {
    public:
      Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
      ~Handle()
      {
        if (id_ >= 0)
          close_(id_);
      }
      Handle(Handle &&other) noexcept : id_(other.id_), close_(other.close_)
      {
        other.id_ = -1;
      }
      Handle(const Handle &)            = delete;
      Handle &operator=(const Handle &) = delete;
      hid_t   get() const
      {
        return id_;
      }
      bool valid() const
      {
        return id_ >= 0;
      }

    private:
      hid_t id_;
      herr_t (*close_)(hid_t);
    };

    template<typename T>
    hid_t native_type()
    {
      static_assert(std::is_same_v<T, double> ||
                    std::is_same_v<T, unsigned int>);
      return std::is_same_v<T, double> ? H5T_NATIVE_DOUBLE : H5T_NATIVE_UINT;
    }

    std::invalid_argument bad_part(const std::string &kind,
                                   const std::string &name,
                                   const std::string &what)
    {
      return std::invalid_argument(kind + " '" + name + "' " + what);
    }

    Handle open_attribute(hid_t file, const std::string &name)
    {
      Handle attribute(H5Aopen(file, name.c_str(), H5P_DEFAULT), H5Aclose);
      if (!attribute.valid())
        throw bad_part("attribute", name, "is missing");
      return attribute;
    }
  } // namespace

  Hdf5Reader::Hdf5Reader(const std::string &path)
      : file_(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT))
  {
    if (file_ < 0)
      throw std::invalid_argument("HDF5 cannot open it for reading");
  }

  Hdf5Reader::~Hdf5Reader()
  {
    H5Fclose(file_);
  }

  bool Hdf5Reader::has_attribute(const std::string &name) const
  {
    return H5Aexists(file_, name.c_str()) > 0;
  }

  bool Hdf5Reader::has_dataset(const std::string &name) const
  {
    return H5Lexists(file_, name.c_str(), H5P_DEFAULT) > 0;
  }

  bool Hdf5Reader::has_string_attribute(const std::string &name) const
  {
    if (!has_attribute(name))
      return false;
    const Handle attribute = open_attribute(file_, name);
    const Handle type(H5Aget_type(attribute.get()), H5Tclose);
    return type.valid() && H5Tget_class(type.get()) == H5T_STRING &&
           H5Tis_variable_str(type.get()) > 0;
  }

  template<typename T>
  T Hdf5Reader::attribute(const std::string &name) const
  {
    const Handle attribute = open_attribute(file_, name);
    const Handle space(H5Aget_space(attribute.get()), H5Sclose);
    T            value{};
    if (!space.valid() || H5Sget_simple_extent_npoints(space.get()) != 1 ||
        H5Aread(attribute.get(), native_type<T>(), &value) < 0)
      throw bad_part("attribute", name, "is not a single number");
    return value;
  }

  std::string Hdf5Reader::string_attribute(const std::string &name) const
  {
    if (!has_string_attribute(name))
      throw bad_part("attribute", name, "is not a string");
    const Handle attribute = open_attribute(file_, name);
    const Handle space(H5Aget_space(attribute.get()), H5Sclose);
    // Several strings would be written past the one pointer below.
    if (!space.valid() || H5Sget_simple_extent_npoints(space.get()) != 1)
      throw bad_part("attribute", name, "is not a single string");
    const Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(type.get(), H5T_VARIABLE);
    H5Tset_cset(type.get(), H5T_CSET_UTF8);
    char *text = nullptr;
    if (H5Aread(attribute.get(), type.get(), &text) < 0)
      throw bad_part("attribute", name, "cannot be read as a string");
    const std::unique_ptr<char, herr_t (*)(void *)> owned(text, H5free_memory);
    return text ? std::string(text) : std::string();
  }

  template<typename T>
  std::vector<T>
  Hdf5Reader::dataset(const std::string         &name,
                      std::vector<unsigned int> *dimensions) const
  {
    const Handle set(H5Dopen2(file_, name.c_str(), H5P_DEFAULT), H5Dclose);
    if (!set.valid())
      throw bad_part("dataset", name, "is missing");
    const Handle space(H5Dget_space(set.get()), H5Sclose);
    const int    rank =
        space.valid() ? H5Sget_simple_extent_ndims(space.get()) : -1;
    if (rank < 0)
      throw bad_part("dataset", name, "has no readable shape");
    std::vector<hsize_t> shape(rank);
    H5Sget_simple_extent_dims(space.get(), shape.data(), nullptr);
    std::vector<T> values(H5Sget_simple_extent_npoints(space.get()));
    if (!values.empty() && H5Dread(set.get(), native_type<T>(), H5S_ALL,
                                   H5S_ALL, H5P_DEFAULT, values.data()) < 0)
      throw bad_part("dataset", name, "cannot be read as numbers");
    if (dimensions)
      dimensions->assign(shape.begin(), shape.end());
    return values;
  }

  template double       Hdf5Reader::attribute(const std::string &) const;
  template unsigned int Hdf5Reader::attribute(const std::string &) const;
  template std::vector<double>
  Hdf5Reader::dataset(const std::string &, std::vector<unsigned int> *) const;
  template std::vector<unsigned int>
  Hdf5Reader::dataset(const std::string &, std::vector<unsigned int> *) const;
} // namespace coshell::io
