#pragma once

#include <map>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace coshell::io
{
  /// Minimal JSON value for writing summaries (numbers, strings, objects,
  /// arrays). Objects keep their keys sorted, so output is reproducible.
  class Json
  {
  public:
    using Object = std::map<std::string, Json>;
    using Array  = std::vector<Json>;

    Json() = default;
    Json(double number);
    Json(int number);
    Json(unsigned int number);
    Json(unsigned long number);
    Json(bool flag);
    Json(const char *text);
    Json(const std::string &text);
    Json(const Object &object);
    Json(const Array &array);

    /// Object access; turns a null value into an object.
    Json &operator[](const std::string &key);

    std::string dump(unsigned int indent = 0) const;

  private:
    std::variant<std::nullptr_t, double, bool, std::string, Object, Array>
        value_;
  };

  /// Writes 'text' to 'path' through a temporary file and a rename, so a
  /// reader never sees a half-written file.
  void write_file_atomically(const std::string &path, const std::string &text);
} // namespace coshell::io
