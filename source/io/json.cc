#include <coshell/base/parallel_environment.h>
#include <coshell/io/json.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace coshell::io
{
  Json::Json(double number) : value_(number) {}
  Json::Json(int number) : value_(static_cast<double>(number)) {}
  Json::Json(unsigned int number) : value_(static_cast<double>(number)) {}
  Json::Json(unsigned long number) : value_(static_cast<double>(number)) {}
  Json::Json(bool flag) : value_(flag) {}
  Json::Json(const char *text) : value_(std::string(text)) {}
  Json::Json(const std::string &text) : value_(text) {}
  Json::Json(const Object &object) : value_(object) {}
  Json::Json(const Array &array) : value_(array) {}

  Json &Json::operator[](const std::string &key)
  {
    if (std::holds_alternative<std::nullptr_t>(value_))
      value_ = Object();
    return std::get<Object>(value_)[key];
  }

  namespace
  {
    std::string quoted(const std::string &text)
    {
      std::ostringstream out;
      out << '"';
      for (const char c : text)
      {
        if (c == '"' || c == '\\')
          out << '\\' << c;
        else if (c == '\n')
          out << "\\n";
        else if (static_cast<unsigned char>(c) < 0x20)
          out << "\\u" << std::hex << std::setw(4) << std::setfill('0')
              << static_cast<int>(c) << std::dec;
        else
          out << c;
      }
      out << '"';
      return out.str();
    }

    std::string number_text(double x)
    {
      if (!std::isfinite(x))
        return "null"; // JSON has no NaN or infinity
      std::ostringstream out;
      out << std::setprecision(17) << x;
      return out.str();
    }
  } // namespace

  std::string Json::dump(unsigned int indent) const
  {
    const std::string pad(indent + 2, ' '), close_pad(indent, ' ');
    if (std::holds_alternative<double>(value_))
      return number_text(std::get<double>(value_));
    if (std::holds_alternative<bool>(value_))
      return std::get<bool>(value_) ? "true" : "false";
    if (std::holds_alternative<std::string>(value_))
      return quoted(std::get<std::string>(value_));
    std::ostringstream out;
    if (const auto *object = std::get_if<Object>(&value_))
    {
      out << "{";
      const char *separator = "\n";
      for (const auto &[key, value] : *object)
      {
        out << separator << pad << quoted(key) << ": "
            << value.dump(indent + 2);
        separator = ",\n";
      }
      out << (object->empty() ? "}" : "\n" + close_pad + "}");
      return out.str();
    }
    if (const auto *array = std::get_if<Array>(&value_))
    {
      out << "[";
      const char *separator = "\n";
      for (const auto &value : *array)
      {
        out << separator << pad << value.dump(indent + 2);
        separator = ",\n";
      }
      out << (array->empty() ? "]" : "\n" + close_pad + "]");
      return out.str();
    }
    return "null";
  }

  void write_file_atomically(const std::string &path, const std::string &text)
  {
    if (!base::writes_output())
      return;
    const std::string temporary = path + ".partial";
    {
      std::ofstream out(temporary);
      out << text;
      if (!out)
        throw std::runtime_error("cannot write '" + temporary + "'");
    }
    std::filesystem::rename(temporary, path);
  }
} // namespace coshell::io
