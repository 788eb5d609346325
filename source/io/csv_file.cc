#include <coshell/io/csv_file.h>

#include <filesystem>
#include <iomanip>
#include <stdexcept>

namespace coshell::io
{
  std::string join(const std::vector<std::string> &names)
  {
    std::string line;
    for (const auto &name : names)
      line += (line.empty() ? "" : ",") + name;
    return line;
  }

  CsvFile::CsvFile(const std::string              &path,
                   const std::vector<std::string> &columns)
      : path_(path)
  {
    const auto directory = std::filesystem::path(path).parent_path();
    if (!directory.empty())
      std::filesystem::create_directories(directory);
    out_.open(path + ".partial");
    if (!out_)
      throw std::runtime_error("cannot write '" + path + ".partial'");
    out_ << join(columns) << '\n' << std::setprecision(12);
  }

  void CsvFile::row(const std::vector<double> &values)
  {
    for (std::size_t i = 0; i < values.size(); ++i)
      out_ << (i ? "," : "") << values[i];
    out_ << std::endl;
  }

  void CsvFile::finish()
  {
    out_.close();
    std::filesystem::rename(path_ + ".partial", path_);
  }

  const std::string &CsvFile::path() const
  {
    return path_;
  }
} // namespace coshell::io
