// An encode of a file as `dcurve encode` runs it: the output checked before the long work,
// the input read, encoded and written in one step, and the summary `--json` prints. The CLI
// and the Python module (python/) both run it, so a file encodes to the same bytes, with the
// same messages, from either.
#pragma once
#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "corpus/input.h"
#include "encoder/encoder.h"

namespace dcurve::cli {

struct EncodeFileJob {
  std::string input, output;
  InputOptions input_options;
  EncodeOptions options;  // its progress is set from the listener
  bool force = false;     // replace an existing output file
};

// Where an encode's messages go: notes (input read but not kept) and details (-v), and a
// progress callback per stage ("simulate" for a scene file, "encode"). Any may be empty.
struct EncodeListener {
  std::function<void(const std::string&)> note, detail;
  std::function<std::function<void(double)>(const std::string& stage)> progress;
};

// Runs `job`. False with the message the CLI prints after "dcurve encode: " (naming the input
// or the output); nothing is written then.
bool run_encode_file(const EncodeFileJob& job, const EncodeListener& listener, EncodeReport* report,
                     std::string* error);

// The one JSON object `dcurve encode --json` prints for a finished job.
nlohmann::json encode_summary_json(const EncodeFileJob& job, const EncodeReport& report);

// The CLI's names of the options the summary reports ("none", "pde8", ...; "small", "fast").
const char* model_choice_name(ModelChoice model);
const char* profile_name(Profile profile);

}  // namespace dcurve::cli
