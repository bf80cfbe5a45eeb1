#pragma once
// A formula from the command line ("r + 1.05*z", "R*sin(pi*z/h)"), parsed
// once and evaluated per point by muparser (Debian's libmuparser-dev: the
// usual operators, ^ for powers, sin cos tan asin acos atan sinh ... exp ln
// log10 sqrt abs sign rint min max, a ? b : c), with `pi` and `e` defined.
//
// Variables are bound by name to doubles the caller owns and sets before
// each evaluate(); a name the caller did not bind is an error when the
// expression is made, as is bad syntax, both with the position (1-based).
// muparser stays behind this header.
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace gcode {

struct ExpressionError : std::invalid_argument {
  ExpressionError(const std::string& message, int position) : std::invalid_argument(message), position(position) {}
  int position;  // 1-based character of the text where it went wrong; 0 unknown
};

using ExpressionVariables = std::vector<std::pair<std::string, double*>>;

class Expression {
 public:
  // Throws ExpressionError ("Unexpected token "q" found at character 5").
  Expression(std::string_view text, const ExpressionVariables& variables);
  ~Expression();
  Expression(Expression&&) noexcept;
  Expression& operator=(Expression&&) noexcept;

  double evaluate() const;  // NaN or an infinity where the formula has one (sqrt(-1), 1/0)
  const std::string& text() const { return text_; }
  // Whether the formula uses a variable (from the parsed text).
  bool uses(std::string_view name) const;

 private:
  struct Parser;
  std::unique_ptr<Parser> parser_;
  std::string text_;
};

}  // namespace gcode
