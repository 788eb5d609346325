#pragma once

#include <fstream>
#include <string>
#include <vector>

namespace coshell::io
{
  /// A CSV result file written row by row to PATH.partial and renamed to
  /// PATH by finish(), so a run that fails leaves no file that looks
  /// complete (the .partial file stays for diagnosis).
  class CsvFile
  {
  public:
    CsvFile(const std::string &path, const std::vector<std::string> &columns);

    /// Writes one row (12 significant digits) and flushes it, so that a
    /// long run can be watched.
    void row(const std::vector<double> &values);
    /// Closes and renames the file.
    void finish();

    const std::string &path() const;

  private:
    std::string   path_;
    std::ofstream out_;
  };

  /// "a,b,c" for the names.
  std::string join(const std::vector<std::string> &names);
} // namespace coshell::io
