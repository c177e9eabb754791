#include "headless_chromium.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "surfgrow/core/text.hpp"
#include "surfgrow/view/base64.hpp"

extern char** environ;

namespace surfgrow::test {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

namespace {

std::string describe(const json& remote) {
    if (remote.contains("value")) return remote["value"].dump();
    return remote.value("description", remote.value("type", std::string("?")));
}

}  // namespace

std::optional<fs::path> HeadlessChromium::find() {
    if (const char* env = std::getenv("SURFGROW_CHROMIUM"); env && *env) {
        if (::access(env, X_OK) == 0) return fs::path(env);
        return std::nullopt;
    }
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path ? path : "/usr/bin:/bin");
    for (std::string dir; std::getline(dirs, dir, ':');)
        for (const char* name : {"chromium", "chromium-browser"}) {
            const fs::path p = fs::path(dir) / name;
            if (::access(p.c_str(), X_OK) == 0) return p;
        }
    return std::nullopt;
}

HeadlessChromium::HeadlessChromium(const fs::path& binary, const fs::path& scratch, int width,
                                   int height) {
    int commands[2], answers[2];
    if (::pipe2(commands, O_CLOEXEC) != 0 || ::pipe2(answers, O_CLOEXEC) != 0)
        throw std::runtime_error("pipe failed");
    const fs::path profile = scratch / "chromium-profile";
    fs::create_directories(profile);
    log_file_ = scratch / "chromium.log";
    const std::vector<std::string> args = {
        binary.string(), "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
        "--no-first-run", "--disable-background-networking", "--disable-component-update",
        "--disable-sync", cat({"--user-data-dir=", profile.string()}),
        // Software WebGL: SwiftShader, which Chromium now wants asked for by name.
        "--enable-unsafe-swiftshader", "--remote-debugging-pipe", "--hide-scrollbars",
        "--mute-audio", "--no-default-browser-check",
        cat({"--window-size=", std::to_string(width), ",", std::to_string(height)}), "about:blank"};
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);

    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    posix_spawn_file_actions_adddup2(&files, commands[0], 3);  // dup2 clears close-on-exec
    posix_spawn_file_actions_adddup2(&files, answers[1], 4);
    posix_spawn_file_actions_addopen(&files, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&files, 1, log_file_.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_adddup2(&files, 1, 2);
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);  // its own group: killable as one
    posix_spawnattr_setpgroup(&attr, 0);
    const int rc = ::posix_spawn(&pid_, binary.c_str(), &files, &attr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&files);
    posix_spawnattr_destroy(&attr);
    ::close(commands[0]);
    ::close(answers[1]);
    to_browser_ = commands[1];
    from_browser_ = answers[0];
    if (rc != 0) {
        pid_ = -1;
        throw std::runtime_error(cat({"cannot start ", binary.string()}));
    }
    ::signal(SIGPIPE, SIG_IGN);  // a browser that died must give an error, not kill the test

    const json target = call("Target.createTarget", {{"url", "about:blank"}}, false);
    const json attached = call("Target.attachToTarget",
                               {{"targetId", target.at("targetId")}, {"flatten", true}}, false);
    session_ = attached.at("sessionId").get<std::string>();
    for (const char* domain : {"Runtime.enable", "Log.enable", "Page.enable", "Network.enable"})
        call(domain, json::object(), true);
    call("Emulation.setDeviceMetricsOverride",
         {{"width", width}, {"height", height}, {"deviceScaleFactor", 1}, {"mobile", false}}, true);
}

HeadlessChromium::~HeadlessChromium() {
    if (pid_ > 0) {
        try {
            send({{"id", next_id_++}, {"method", "Browser.close"}, {"params", json::object()}});
        } catch (...) {
        }
        const auto deadline = Clock::now() + std::chrono::seconds(10);
        int status = 0;
        while (::waitpid(pid_, &status, WNOHANG) == 0) {
            if (Clock::now() > deadline) {
                ::kill(-pid_, SIGKILL);  // the group we created for it: our child and its helpers
                ::waitpid(pid_, &status, 0);
                break;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
    }
    if (to_browser_ >= 0) ::close(to_browser_);
    if (from_browser_ >= 0) ::close(from_browser_);
}

void HeadlessChromium::send(const json& message) {
    const std::string text = message.dump() + '\0';
    std::size_t done = 0;
    while (done < text.size()) {
        const ssize_t n = ::write(to_browser_, text.data() + done, text.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw std::runtime_error("chromium closed its command pipe");
        done += static_cast<std::size_t>(n);
    }
}

bool HeadlessChromium::receive(json& message, Clock::time_point deadline) {
    while (true) {
        const auto end = buffer_.find('\0');
        if (end != std::string::npos) {
            message = json::parse(buffer_.substr(0, end));
            buffer_.erase(0, end + 1);
            return true;
        }
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
        if (left.count() <= 0) return false;
        pollfd p{from_browser_, POLLIN, 0};
        const int ready = ::poll(&p, 1, static_cast<int>(left.count()));
        if (ready < 0 && errno == EINTR) continue;
        if (ready <= 0) return false;
        char chunk[65536];
        const ssize_t n = ::read(from_browser_, chunk, sizeof chunk);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw std::runtime_error(cat({"chromium closed its answer pipe\n", log()}));
        buffer_.append(chunk, static_cast<std::size_t>(n));
    }
}

void HeadlessChromium::on_event(const json& m) {
    const std::string method = m.value("method", "");
    const json& p = m.contains("params") ? m["params"] : json::object();
    if (method == "Runtime.consoleAPICalled") {
        std::string text = cat({p.value("type", ""), ":"});
        for (const json& a : p.value("args", json::array())) text += cat({" ", describe(a)});
        const std::string type = p.value("type", "");
        if (type == "error" || type == "assert") errors_.push_back(text);
        if (type == "warning") warnings_.push_back(text);
    } else if (method == "Runtime.exceptionThrown") {
        const json& d = p.at("exceptionDetails");
        errors_.push_back(
            cat({"exception: ", d.contains("exception") ? describe(d["exception"])
                                                        : d.value("text", std::string("?"))}));
    } else if (method == "Log.entryAdded") {
        const json& e = p.at("entry");
        const std::string text = cat({e.value("source", ""), ": ", e.value("text", "")});
        if (e.value("level", "") == "error") errors_.push_back(text);
        if (e.value("level", "") == "warning") warnings_.push_back(text);
    } else if (method == "Network.requestWillBeSent") {
        requests_.push_back(p.at("request").value("url", ""));
    } else if (method == "Page.loadEventFired") {
        loaded_ = true;
    }
}

json HeadlessChromium::call(const std::string& method, const json& params, bool on_page,
                            std::chrono::milliseconds timeout) {
    const int id = next_id_++;
    json message = {{"id", id}, {"method", method}, {"params", params}};
    if (on_page) message["sessionId"] = session_;
    send(message);
    const auto deadline = Clock::now() + timeout;
    json m;
    while (receive(m, deadline)) {
        if (m.value("id", 0) != id) {
            on_event(m);
            continue;
        }
        if (m.contains("error"))
            throw std::runtime_error(cat({method, " failed: ", m["error"].dump()}));
        return m.value("result", json::object());
    }
    throw std::runtime_error(cat({method, ": no answer from chromium\n", log()}));
}

void HeadlessChromium::open(const std::string& url) {
    loaded_ = false;
    call("Page.navigate", {{"url", url}}, true);
    const auto deadline = Clock::now() + std::chrono::seconds(60);
    json m;
    while (!loaded_ && receive(m, deadline)) on_event(m);
    if (!loaded_) throw std::runtime_error(cat({"no load event from ", url}));
}

json HeadlessChromium::evaluate(const std::string& expression) {
    const json r =
        call("Runtime.evaluate",
             {{"expression", expression}, {"returnByValue", true}, {"awaitPromise", true}}, true);
    if (r.contains("exceptionDetails"))
        throw std::runtime_error(
            cat({"evaluating ", expression, ": ", r["exceptionDetails"].dump()}));
    return r.at("result").value("value", json());
}

bool HeadlessChromium::wait_until(const std::string& expression,
                                  std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (Clock::now() < deadline) {
        if (evaluate(expression) == true) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
}

std::string HeadlessChromium::screenshot_png() {
    const json r = call("Page.captureScreenshot", {{"format", "png"}}, true);
    const auto png = view::decode_base64(r.at("data").get<std::string>());
    if (!png) throw std::runtime_error("Page.captureScreenshot: data is not base64");
    return *png;
}

std::string HeadlessChromium::log() const {
    std::ifstream in(log_file_);
    std::stringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    if (text.size() > 4000) text = cat({"...", text.substr(text.size() - 4000)});
    return text;
}

}  // namespace surfgrow::test
