#pragma once
// The command line's value parsers, shared by the depthtrack command and the peer runners
// (bench/peers compile this file with them).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace depthtrack::cli {

// "WxH" -> (W, H); InputError for anything else.
std::pair<int, int> parse_resolution(const std::string& text);
// "a b c ..." -> exactly n numbers; InputError naming the option otherwise.
std::vector<double> parse_numbers(const std::string& text, size_t n, const std::string& option);
// A random seed: a whole number in [0, 2^64 - 1] written in decimal digits; InputError naming the
// option for a sign, a fraction, an exponent or a value out of range.
uint64_t parse_seed(const std::string& text, const std::string& option);

}  // namespace depthtrack::cli
