#pragma once
// What `tellus bench` runs: each renderer of --algo with its options, and with --vary the
// same renderer once per value of one option, all along the same path and judged against the
// same truth (made once). A sweep of a renderer's option then costs one truth, not one a value.
#include <string>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/render/registry/renderer_registry.hpp"

namespace tellus::cli {

struct BenchEntry {
  std::string algo;   // the renderer (rendererTable's name)
  std::string label;  // the name it is reported under: algo, or "stacks[stack-updates=400]"
  RendererSettings settings;  // every family's options for this run
};

// `algos` in order, each with `settings`. With `vary` ("OPTION=V1,V2,...", OPTION an option's
// key as in the report: "stack-updates", "roam-target"), each renderer whose family has
// that option is listed once per value, in the order given; the others once. Errors: a
// malformed `vary`, an option no listed renderer's family has, a value the option refuses, a
// value given twice.
Result<std::vector<BenchEntry>> benchEntries(const std::vector<std::string>& algos,
                                             const RendererSettings& settings,
                                             const std::string& vary);

// The labels of `entries`, in order.
std::vector<std::string> benchLabels(const std::vector<BenchEntry>& entries);

}  // namespace tellus::cli
