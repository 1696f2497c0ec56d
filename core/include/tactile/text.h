#pragma once
// Numbers and names as the programs print them, written once for every report and message.

#include <string>
#include <vector>

namespace tactile {

// The shortest text that reads back as the same double ("0.1", "1e-07"): for files and for
// error messages that quote a value.
std::string shortest_text(double value);

// A time in seconds to the microsecond, the finest a recording's clock resolves, in its
// shortest form: 4.4639999999999995 -> "4.464", 1.5 -> "1.5", 0.0000004 -> "0".
std::string seconds_text(double seconds);

// `value` with `decimals` digits after the point ("81.80"): for report tables.
std::string fixed_text(double value, int decimals);

// `value` with at most `digits` significant digits, printf's %g ("0.2346").
std::string significant_text(double value, int digits);

// "text" in double quotes, for messages that name a field or an id.
std::string in_quotes(const std::string& text);

// Bytes from a file as a message can print them: control bytes (a NUL among them, which
// would cut the message short), DEL and bytes that are not UTF-8 become \xHH ("\xFE\x00");
// printable ASCII and whole UTF-8 characters stay as they are.
std::string printable_text(const std::string& bytes);

// The items with `separator` between them ("nao, tsa, fur"): lists in help and errors.
std::string joined(const std::vector<std::string>& items, const std::string& separator = ", ");

}  // namespace tactile
