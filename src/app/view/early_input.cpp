#include "app/view/early_input.h"

#include <algorithm>

#include "common/fault_injection.h"

namespace sm::view {
namespace {

bool isQuit(const InputEvent& e) {
  return e.type == InputEvent::Type::Quit ||
         (e.type == InputEvent::Type::KeyPress && e.key == Key::Quit);
}

}  // namespace

bool EarlyInput::quitArrived() {
  const size_t before = early_.size();
  window_.poll(early_);
  quit_ = quit_ || window_.closeRequested() || fault::closeAtRangePass() ||
          std::any_of(early_.begin() + std::ptrdiff_t(before), early_.end(), isQuit);
  return quit_;
}

bool EarlyInput::takeFrame(std::vector<InputEvent>& events) {
  events.insert(events.begin(), early_.begin(), early_.end());
  early_.clear();
  window_.poll(events);
  quit_ = false;
  return script_.nextFrame(events);
}

}  // namespace sm::view
