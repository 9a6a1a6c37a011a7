#pragma once
// The command line's value parsers, shared by the depthtrack command and the peer runners
// (bench/peers compile this file with them).
#include <string>
#include <utility>
#include <vector>

namespace depthtrack::cli {

// "WxH" -> (W, H); InputError for anything else.
std::pair<int, int> parse_resolution(const std::string& text);
// "a b c ..." -> exactly n numbers; InputError naming the option otherwise.
std::vector<double> parse_numbers(const std::string& text, size_t n, const std::string& option);

}  // namespace depthtrack::cli
