// JSON fragments shared by the sub-commands' reports.
#pragma once
#include <chrono>
#include <string>
#include <vector>

#include "dcshell/certify.h"
#include "dcshell/json.h"

namespace dcshell::cli {

/// Writes "certified", "meshes" (per mesh verdict) and "overlaps" (per overlapping pair, by name)
/// as fields of the current JSON object.
void write_certification(JsonWriter& json, const CertificationReport& report, const std::vector<std::string>& names);

/// One line per problem on stderr: why a mesh is not convex, which pairs overlap and by how much.
void print_certification_problems(const CertificationReport& report, const std::vector<std::string>& names);

/// Seconds since `start` (steady clock), for "time" fields.
double seconds_since(const std::chrono::steady_clock::time_point& start);

}  // namespace dcshell::cli
