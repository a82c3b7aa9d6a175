#pragma once
// Numbers typed by a person (`--set key=value`, command-line flags, the editor's fields) read without
// silent conversion: a whole number must be written in decimal digits (an optional minus sign, no
// fraction, no octal or hex) and lie within its limits, never wrapping (10000000000 into a 32-bit int,
// -1 into an unsigned seed); a real number must be finite (NaN and infinity are refused by name).
// Each function returns "" when the text is fine, else the problem as a sentence that says the limits.
#include <cstdint>
#include <string>

namespace goris {

// `text` as a whole number in [min, max]; `value` receives it when the text is fine.
std::string parse_whole_number(const std::string& text, long double min, long double max, long double& value);
// `text` as a finite real number in [min, max].
std::string parse_real_number(const std::string& text, double min, double max, double& value);
// "NaN"/"inf"/"-infinity"... in any case: the words a person might write for a non-finite number.
bool names_non_finite_number(const std::string& text);
// A limit as a person writes it: 2147483647, 0.5, 1e+30.
std::string limit_text(long double v);

}  // namespace goris
