#pragma once
// How an error names the field at fault when one description is filled from several places: the command line
// and scene files build their terrain, grass and forests through the same engine functions, and each error
// names what the user wrote.

#include <functional>
#include <string>
#include <string_view>

namespace sylva {

/**
 * Turns a field's scene-file name ("size", "max_slope", "bark", …) into what the user wrote: "--size" on the
 * command line, "meadow.json: /terrain/size" in a scene file. An empty FieldName leaves the name as it is.
 */
using FieldName = std::function<std::string(std::string_view field)>;

/** `name(field)`, or `field` itself when `name` is empty. */
inline std::string fieldName(const FieldName& name, std::string_view field) {
  return name ? name(field) : std::string(field);
}

} // namespace sylva
