#pragma once
// The one place numbers from the command line are checked. Every option that takes a number
// gets a range through numberIn() or integerIn(): the text is checked before CLI11 converts it,
// so "nan", "inf", "1e308", or "-1" for an unsigned option are refused with the range in a
// readable form, instead of slipping through comparisons (NaN compares false with everything)
// or wrapping around.
#include <cstdint>

#include <CLI/CLI.hpp>

namespace tellus::cli {

// A finite real number within [lo, hi].
CLI::Validator numberIn(double lo, double hi);
// An integer (no fraction, no exponent) within [lo, hi].
CLI::Validator integerIn(std::int64_t lo, std::int64_t hi);

// Gives every option of `app` and its subcommands that takes a number but has no check at all
// (no numberIn() or integerIn() range, no list of allowed values) a finite-number check. A
// safety net: the CLI tests require every numeric option to refuse out-of-range values too.
void requireFiniteNumbers(CLI::App& app);

// Gives every option of `app` and its subcommands that takes a value a check refusing the empty
// one: `--geo-camera ""` is a mistake (an unset shell variable), never "the default".
void refuseEmptyValues(CLI::App& app);

}  // namespace tellus::cli
