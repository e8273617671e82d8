// How each front end names a setting that a SettingError (common/setting_error.h) is keyed by.
// The command line shows the option (--colormap, which SettingError::what() already is); the
// in-situ API shows the field of its RenderSettings (sampleDistance for step) and the Python
// module its keyword argument (log_scale for log-scale).
#pragma once

#include <string>

#include "common/setting_error.h"

namespace sm::session {

// The in-situ API's name for setting `key`: its RenderSettings field, camelCase.
std::string apiName(const std::string& key);
// The Python module's keyword argument for `key`: snake_case.
std::string pythonName(const std::string& key);

// "<name>: <detail>" with the in-situ API's or the Python module's name for e's setting.
std::string apiMessage(const SettingError& e);
std::string pythonMessage(const SettingError& e);

}  // namespace sm::session
