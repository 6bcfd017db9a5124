// The arguments of an input command read in turn: fix cell/servo's programme arguments and
// keywords (docs/fix_cell_servo.md). Numbers must be finite ("1e400" overflows to inf in
// strtod and is refused as such), numbers of a bounded quantity must lie in their range, and
// a number that may follow the state of the run is a Setting: a number or `v_name`, an
// equal-style variable the caller evaluates every step. Every error is a std::invalid_argument
// whose message names the argument and what is accepted; the LAMMPS style puts its own name in
// front ("fix cell/servo: ..."). Plain C++, no LAMMPS: tested by tests/core/test_command_args.cpp.
#ifndef TYCORE_COMMAND_ARGS_HPP
#define TYCORE_COMMAND_ARGS_HPP

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace tycore {

// a number as %g writes it (the ranges of the messages)
inline std::string g_text(double value)
{
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// A number given in the command, or an equal-style variable (`v_name`) the caller evaluates
// every step; its evaluation is checked against `sign` (a target stress is compressive) and,
// for a stress, against MAX_STRESS
struct Setting {
  enum class Sign { ANY, POSITIVE, NOT_NEGATIVE };
  enum class Kind { STRAIN_RATE, STRESS };
  double value = 0.0;      // the number, or the variable's last value
  std::string variable;    // the variable's name (without v_); empty for a number
  std::string what;        // the argument, for messages: "axisym axial strain rate"
  Kind kind = Kind::STRAIN_RATE;
  Sign sign = Sign::ANY;
  std::string sign_reason;    // why the sign is required (messages)

  bool is_variable() const { return !variable.empty(); }
  // why a value of the variable is refused ("" if it is not)
  std::string refusal(double v) const;
};

// A stress beyond any granular material's [Pa]: a larger target is an input error, not a test
// (in 1/s it would otherwise surface as a strain rate the cell cannot follow)
constexpr double MAX_STRESS = 1e15;

inline std::string Setting::refusal(double v) const
{
  if (!std::isfinite(v)) return "not a finite number";
  if ((sign == Sign::POSITIVE && !(v > 0.0)) || (sign == Sign::NOT_NEGATIVE && v < 0.0))
    return sign_reason;
  if (kind == Kind::STRESS && !(std::fabs(v) <= MAX_STRESS))
    return "a stress beyond 1e+15 Pa, beyond any granular material";
  return "";
}

// what a Setting evaluates to at this step (the fix: LAMMPS's equal-style variables)
class SettingValues {
 public:
  virtual double operator()(Setting &setting) = 0;

 protected:
  ~SettingValues() = default;
};

// the arguments args[at...] of a command; `next` and the readers advance
class ArgList {
 public:
  explicit ArgList(std::vector<std::string> args, std::size_t at = 0) :
      args_(std::move(args)), at_(at)
  {
  }

  bool done() const { return at_ >= args_.size(); }
  std::size_t position() const { return at_; }
  std::size_t remaining() const { return done() ? 0 : args_.size() - at_; }
  const std::string &peek() const
  {
    static const std::string none;
    return done() ? none : args_[at_];
  }

  // the next argument, `what` naming it when it is missing
  const std::string &next(const std::string &what)
  {
    if (done()) throw std::invalid_argument(what + " is missing");
    return args_[at_++];
  }

  // n more arguments must follow; `usage` is the command's form
  void need(std::size_t n, const std::string &usage) const
  {
    if (remaining() < n)
      throw std::invalid_argument("expected " + std::to_string(n) + " more argument(s): " + usage);
  }

  // a finite number; "1e400" (inf after strtod), "inf", "nan" and "abc" are refused by name
  double number(const std::string &what) { return finite_number(next(what), what); }

  static double finite_number(const std::string &text, const std::string &what)
  {
    char *end = nullptr;
    const double parsed = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0')
      throw std::invalid_argument(what + " must be a number, got '" + text + "'");
    if (!std::isfinite(parsed)) {
      const bool overflow = !std::isnan(parsed) && !std::strpbrk(text.c_str(), "iI");
      throw std::invalid_argument(what + " must be a finite number, got '" + text + "'" +
                                  (overflow ? " (it overflows to infinity)" : ""));
    }
    return parsed;
  }

  // a number in [lo, hi], or (lo, hi] with open_low; the message states the range
  double number_in(const std::string &what, double lo, double hi, bool open_low,
                   const std::string &unit = "")
  {
    const std::string &text = next(what);
    const double v = finite_number(text, what);
    if ((open_low ? !(v > lo) : !(v >= lo)) || !(v <= hi))
      throw std::invalid_argument(what + " = " + text + " is outside the accepted range " +
                                  (open_low ? "(" : "[") + g_text(lo) + ", " + g_text(hi) + "]" +
                                  unit);
    return v;
  }

  int positive_integer(const std::string &what)
  {
    const std::string &text = next(what);
    char *end = nullptr;
    const long value = std::strtol(text.c_str(), &end, 10);
    if (end == text.c_str() || *end != '\0' || value <= 0 ||
        value > std::numeric_limits<int>::max())
      throw std::invalid_argument(what + " must be a positive integer, got '" + text + "'");
    return static_cast<int>(value);
  }

  bool yes_no(const std::string &what)
  {
    const std::string &v = next(what);
    if (v != "yes" && v != "no")
      throw std::invalid_argument(what + " must be yes or no, got '" + v + "'");
    return v == "yes";
  }

  // one of the words `choices`, returned as its index
  int choice(const std::string &what, const std::vector<std::string> &choices)
  {
    const std::string &v = next(what);
    for (std::size_t k = 0; k < choices.size(); ++k)
      if (v == choices[k]) return static_cast<int>(k);
    std::string list;
    for (std::size_t k = 0; k < choices.size(); ++k)
      list += (k == 0 ? "" : k + 1 == choices.size() ? " or " : ", ") + choices[k];
    throw std::invalid_argument(what + " must be " + list + ", got '" + v + "'");
  }

  // a Setting: `v_name` or a finite number
  Setting setting(const std::string &what, Setting::Kind kind = Setting::Kind::STRAIN_RATE)
  {
    const std::string &text = next(what);
    Setting s;
    s.what = what;
    s.kind = kind;
    if (text.compare(0, 2, "v_") == 0)
      s.variable = text.substr(2);
    else
      s.value = finite_number(text, what);
    if (kind == Setting::Kind::STRESS && !s.is_variable() && !(std::fabs(s.value) <= MAX_STRESS))
      throw std::invalid_argument(what + " = " + text + " is outside the accepted range [-" +
                                  g_text(MAX_STRESS) + ", " + g_text(MAX_STRESS) +
                                  "] Pa (beyond any granular material)");
    return s;
  }

  // a target stress: a positive number up to MAX_STRESS (a granular cell carries no tension)
  double stress(const std::string &what)
  {
    const std::string &text = next(what);
    const double v = finite_number(text, what);
    if (!(v > 0.0))
      throw std::invalid_argument("target " + what + " = " + text +
                                  " must be positive (a "
                                  "granular cell carries no tension)");
    if (!(v <= MAX_STRESS))
      throw std::invalid_argument("target " + what + " = " + text + " is above " +
                                  g_text(MAX_STRESS) + " Pa, beyond any granular material");
    return v;
  }

 private:
  std::vector<std::string> args_;
  std::size_t at_;
};

}    // namespace tycore

#endif
