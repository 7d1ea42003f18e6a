#pragma once
// Key presses queued as the window system reports them (GLFW's key callback), read once per
// frame. ImGui 1.86 samples each key's state once per frame, so a tap whose press and release
// both arrive within one frame (frames reach 0.7 s while a pass renders) never shows as
// pressed there; a queued press does.
#include <algorithm>
#include <vector>

namespace edacrt::app {

class KeyPresses {
  public:
    /// A press of `key` (a GLFW key code) with the modifier bits `mods`, or its auto-repeat.
    void press(int key, int mods, bool repeat) { presses_.push_back({key, mods, repeat}); }

    /// How often `key` was pressed since clear() with at least the modifiers `mods` held and
    /// none of `without`; auto-repeats count too when `repeats`.
    int count(int key, int mods = 0, bool repeats = false, int without = 0) const {
        return int(std::count_if(presses_.begin(), presses_.end(), [&](const Press& p) {
            return p.key == key && (p.mods & mods) == mods && (p.mods & without) == 0 &&
                   (repeats || !p.repeat);
        }));
    }
    bool pressed(int key, int mods = 0) const { return count(key, mods) > 0; }

    /// The frame has read them.
    void clear() { presses_.clear(); }

  private:
    struct Press {
        int key, mods;
        bool repeat;
    };
    std::vector<Press> presses_;
};

}  // namespace edacrt::app
