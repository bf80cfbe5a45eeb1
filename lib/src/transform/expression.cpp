#include "gcode/transform/expression.hpp"

#include <muParser.h>

#include <cmath>
#include <numbers>
#include <string>

namespace gcode {

struct Expression::Parser {
  mu::Parser parser;
};

Expression::Expression(std::string_view text, const ExpressionVariables& variables)
    : parser_(std::make_unique<Parser>()), text_(text) {
  try {
    mu::Parser& p = parser_->parser;
    p.DefineConst("pi", std::numbers::pi);
    p.DefineConst("e", std::numbers::e);
    for (const auto& [name, value] : variables) p.DefineVar(name, value);
    p.SetExpr(text_);
    (void)p.Eval();  // parses now: bad syntax and unknown names are errors here, not at the first point
  } catch (const mu::Parser::exception_type& e) {
    // muparser counts from 0 ("found at position 8."); people count characters from 1.
    const int position = e.GetPos() >= 0 ? static_cast<int>(e.GetPos()) + 1 : 0;
    std::string message = e.GetMsg();
    const std::size_t at = message.find(" at position ");
    if (at != std::string::npos) message.erase(at);
    while (!message.empty() && (message.back() == '.' || message.back() == ' ')) message.pop_back();
    if (position > 0) message += " at character " + std::to_string(position);
    throw ExpressionError(message, position);
  }
}

Expression::~Expression() = default;
Expression::Expression(Expression&&) noexcept = default;
Expression& Expression::operator=(Expression&&) noexcept = default;

double Expression::evaluate() const {
  try {
    return parser_->parser.Eval();
  } catch (const mu::Parser::exception_type&) {
    return std::nan("");  // muparser 2.3 reports some domain errors by throwing
  }
}

bool Expression::uses(std::string_view name) const {
  const mu::varmap_type used = parser_->parser.GetUsedVar();
  return used.find(std::string(name)) != used.end();
}

}  // namespace gcode
