// The built-in scenes: scene files (JSON, the same format users write) generated in code,
// each naming a procedural surface from corpus/surfaces.h.
#pragma once
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace dcurve::corpus {

// Names of the built-in scenes; "rope-small" (the quick default) comes first.
std::vector<std::string> builtin_scene_names();

// The scene file of a built-in scene; false when `name` is unknown.
bool builtin_scene_json(const std::string& name, nlohmann::json* scene);

}  // namespace dcurve::corpus
