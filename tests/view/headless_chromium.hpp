// Debian's Chromium, headless, driven over the DevTools protocol (CDP) on a pipe: open a page
// from disk, run JavaScript in it, take screenshots, and collect console errors, uncaught
// exceptions and network requests. For the viewer's browser tests; no Python, Node or websocket
// library needed.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace surfgrow::test {

class HeadlessChromium {
  public:
    /// $SURFGROW_CHROMIUM, else chromium or chromium-browser on the PATH; nullopt if none.
    [[nodiscard]] static std::optional<std::filesystem::path> find();

    /// Starts `binary` headless (as root: no sandbox; software WebGL through SwiftShader) with a
    /// fresh profile in `scratch`, and opens a blank page of width x height CSS pixels.
    /// Throws std::runtime_error if it does not start or answer.
    HeadlessChromium(const std::filesystem::path& binary, const std::filesystem::path& scratch,
                     int width, int height);
    /// Closes the browser; kills it (its process group) if it does not exit.
    ~HeadlessChromium();
    HeadlessChromium(const HeadlessChromium&) = delete;
    HeadlessChromium& operator=(const HeadlessChromium&) = delete;

    /// Opens `url` and waits for its load event.
    void open(const std::string& url);
    /// Evaluates a JavaScript expression in the page; its value (returnByValue). Throws on an
    /// exception in the page.
    nlohmann::json evaluate(const std::string& expression);
    /// Evaluates `expression` every 50 ms until it is true; false after `timeout`.
    bool wait_until(const std::string& expression, std::chrono::milliseconds timeout);
    /// The page as it is now, as PNG bytes.
    std::string screenshot_png();

    /// console.error / console.assert calls, uncaught exceptions and error log entries so far.
    [[nodiscard]] const std::vector<std::string>& errors() const { return errors_; }
    /// Console warnings and warning log entries so far (reported, not failures).
    [[nodiscard]] const std::vector<std::string>& warnings() const { return warnings_; }
    /// URLs of every request the page made.
    [[nodiscard]] const std::vector<std::string>& requests() const { return requests_; }
    /// Chromium's own stdout and stderr, for failure messages.
    [[nodiscard]] std::string log() const;

  private:
    nlohmann::json call(const std::string& method, const nlohmann::json& params, bool on_page,
                        std::chrono::milliseconds timeout = std::chrono::seconds(60));
    void send(const nlohmann::json& message);
    // Reads one message; false on timeout.
    bool receive(nlohmann::json& message, std::chrono::steady_clock::time_point deadline);
    void on_event(const nlohmann::json& message);

    pid_t pid_ = -1;
    int to_browser_ = -1;    // our end of the pipe Chromium reads commands from (its fd 3)
    int from_browser_ = -1;  // our end of the pipe it writes answers and events to (its fd 4)
    std::string buffer_;
    int next_id_ = 1;
    std::string session_;
    bool loaded_ = false;
    std::filesystem::path log_file_;
    std::vector<std::string> errors_, warnings_, requests_;
};

}  // namespace surfgrow::test
