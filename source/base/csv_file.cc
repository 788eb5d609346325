#include <coshell/base/csv_file.h>
#include <coshell/base/parallel_environment.h>

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <stdexcept>

namespace coshell::base
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
    header_ = join(columns);
    // Under mpirun rank 0 writes; the stream stays closed elsewhere.
    if (!base::writes_output())
      return;
    const auto directory = std::filesystem::path(path).parent_path();
    if (!directory.empty())
      std::filesystem::create_directories(directory);
    out_.open(path + ".partial");
    if (!out_)
      throw std::runtime_error("cannot write '" + path + ".partial'");
    out_ << header_ << '\n' << std::setprecision(csv_digits);
  }

  unsigned int CsvFile::rows() const
  {
    return rows_;
  }

  bool CsvFile::resume(const std::string &earlier)
  {
    const auto header_end = earlier.find('\n');
    if (header_end == std::string::npos ||
        earlier.substr(0, header_end) != header_)
      return false;
    const std::string rows = earlier.substr(header_end + 1);
    out_ << rows;
    out_.flush();
    rows_ += std::count(rows.begin(), rows.end(), '\n');
    return true;
  }

  const std::vector<std::string> &run_csv_files()
  {
    static const std::vector<std::string> files = {
        "load_displacement.csv", "newton_history.csv",   "time_history.csv",
        "contact_forces.csv",    "reference_points.csv", "modes.csv",
        "convergence.csv"};
    return files;
  }

  std::string read_earlier_rows(const std::string &path, unsigned int rows)
  {
    std::ifstream in(path);
    if (!in)
      in.open(path + ".partial");
    std::string text, line;
    for (unsigned int n = 0; n <= rows; ++n)
    {
      if (!std::getline(in, line))
        return "";
      text += line + '\n';
    }
    return text;
  }

  void CsvFile::row(const std::vector<double> &values)
  {
    for (std::size_t i = 0; i < values.size(); ++i)
      out_ << (i ? "," : "") << values[i];
    out_ << std::endl;
    ++rows_;
  }

  void CsvFile::finish()
  {
    if (!out_.is_open())
      return;
    out_.close();
    std::filesystem::rename(path_ + ".partial", path_);
  }

  const std::string &CsvFile::path() const
  {
    return path_;
  }
} // namespace coshell::base
