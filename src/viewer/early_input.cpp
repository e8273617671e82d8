#include "viewer/early_input.h"

#include <algorithm>

#include "common/fault_injection.h"

namespace sm::view {
namespace {

bool isQuit(const InputEvent& e) {
  return e.type == InputEvent::Type::Quit ||
         (e.type == InputEvent::Type::KeyPress && e.key == Key::Quit);
}

}  // namespace

PassInterrupt EarlyInput::interruptArrived() {
  const size_t before = early_.size();
  window_.poll(early_);
  const fault::RangePassInput injected = fault::atRangePass();
  if (injected == fault::RangePassInput::NextField)
    early_.push_back({InputEvent::Type::KeyPress, 0, 0, Button::Left, Key::NextField});
  const auto arrived = early_.begin() + std::ptrdiff_t(before);
  quit_ = quit_ || window_.closeRequested() || injected == fault::RangePassInput::Close ||
          std::any_of(arrived, early_.end(), isQuit);
  fieldChange_ = fieldChange_ || std::any_of(arrived, early_.end(), [](const InputEvent& e) {
                   return e.type == InputEvent::Type::KeyPress && e.key == Key::NextField;
                 });
  return quit_          ? PassInterrupt::Quit
         : fieldChange_ ? PassInterrupt::FieldChange
                        : PassInterrupt::None;
}

bool EarlyInput::takeFrame(std::vector<InputEvent>& events) {
  events.insert(events.begin(), early_.begin(), early_.end());
  early_.clear();
  window_.poll(events);
  quit_ = fieldChange_ = false;
  return script_.nextFrame(events);
}

}  // namespace sm::view
