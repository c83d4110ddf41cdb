#pragma once
/// \file RunSpecJson.hpp
/// \brief Core-internal: the run specification's JSON codec at the level of nlohmann::json values, for the
/// files that embed parameters in a larger document (run files, portrait and b₂ sidecars).  Everything
/// outside core uses the text-level functions of RunSpec.hpp.

#include <nlohmann/json.hpp>
#include <string_view>

#include "core/runspec/RunSpec.hpp"

namespace archipelago::spec {

/// {"K", "xmin", "xmax"}.
[[nodiscard]] nlohmann::json mapJson(const MapParameters& map);

/// Every field of TrappingParameters, keys as in runSpecParameters(), in that order.
[[nodiscard]] nlohmann::json parametersJson(const TrappingParameters& p);

/// Reads a "parameters" object.  Missing keys keep the value in `defaults` unless `complete` is true, when
/// they are errors.  Throws io::BadFile naming the key (unknown key, wrong type, fractional or
/// out-of-range integer, missing key).  Does not check the parameters' rules (validationError does).
[[nodiscard]] TrappingParameters parametersFromJson(const nlohmann::json& j, bool complete,
                                                    const TrappingParameters& defaults = {});

/// Parses a versioned document (io::parseJson: depth-limited, strict about repeated keys): a JSON object whose "format" is `format` and whose "version" is `version`.
/// Throws io::BadFile naming the document ("a" + " run spec", "an" + " Archipelago session") otherwise.
/// The same check on a parsed document.
void checkVersionedDocument(const nlohmann::json& document, const char* format, int version, const std::string& article,
                            const std::string& noun);
[[nodiscard]] nlohmann::json parseVersionedDocument(std::string_view text, const char* format, int version,
                                                    const std::string& article, const std::string& noun);

}  // namespace archipelago::spec
