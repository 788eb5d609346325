#pragma once

#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace coshell::base
{
  /// Significant digits of every number in a CSV result: enough to read
  /// back the double that was written. Fewer turn a round-off difference
  /// of 1e-16 into one unit of the last printed digit, 3e-12 relative at
  /// 12 digits and 3e-10 at 10, which is coarser than the 1e-12 and 1e-10
  /// by which the tests compare two runs that must agree to round-off.
  constexpr int csv_digits = std::numeric_limits<double>::max_digits10;

  /// A CSV result file written row by row to PATH.partial and renamed to
  /// PATH by finish(), so a run that fails leaves no file that looks
  /// complete (the .partial file stays for diagnosis).
  class CsvFile
  {
  public:
    CsvFile(const std::string &path, const std::vector<std::string> &columns);

    /// Writes one row (csv_digits significant digits) and flushes it, so that a
    /// long run can be watched.
    void row(const std::vector<double> &values);
    /// Closes and renames the file.
    void finish();
    /// Rows written so far (the header not counted).
    unsigned int rows() const;
    /// Appends the rows of 'earlier' (a header line and rows, as
    /// read_earlier_rows() returns) when its header is this file's
    /// (a restart). Returns false, appending nothing, otherwise.
    bool resume(const std::string &earlier);

    const std::string &path() const;

  private:
    std::string   path_, header_;
    std::ofstream out_;
    unsigned int  rows_ = 0;
  };

  /// The header and first 'rows' rows of an earlier run's CSV file (PATH,
  /// or PATH.partial if the run did not finish), read before a new run
  /// overwrites it; "" when it is missing or shorter.
  std::string read_earlier_rows(const std::string &path, unsigned int rows);

  /// The CSV files a run writes itself in its output directory (besides
  /// a field's NAME.vertices.csv): an obstacle's Force file may not take
  /// their names.
  const std::vector<std::string> &run_csv_files();

  /// "a,b,c" for the names.
  std::string join(const std::vector<std::string> &names);
} // namespace coshell::base
