// Replays fuzz inputs without libFuzzer: every regular file under the folders given (in name
// order) goes once through LLVMFuzzerTestOneInput. A crash, a sanitizer report or an escaped
// exception fails the test; a folder that does not exist is skipped (crashes/<target>/ is often
// empty, and git keeps no empty folders), but at least one input must have run.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

int main(int argc, char** argv) {
    namespace fs = std::filesystem;
    // Each input on its own, as the product sees it (cli_args otherwise reuses its definition).
    setenv("SURFGROW_FUZZ_FRESH_APP", "1", 0);
    std::vector<fs::path> files;
    for (int i = 1; i < argc; ++i) {
        std::error_code ec;
        if (!fs::is_directory(argv[i], ec)) {
            std::printf("skipping %s (no such folder)\n", argv[i]);
            continue;
        }
        for (const auto& entry : fs::recursive_directory_iterator(argv[i]))
            if (entry.is_regular_file()) files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) {
        std::string bytes(static_cast<std::size_t>(fs::file_size(file)), '\0');
        std::ifstream in(file, std::ios::binary);
        in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        if (!in) {
            std::fprintf(stderr, "cannot read %s\n", file.c_str());
            return 1;
        }
        std::printf("%s\n", file.c_str());
        std::fflush(stdout);  // the input a crash happened on is the last line printed
        LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    }
    std::printf("%zu inputs replayed\n", files.size());
    return files.empty() ? 1 : 0;
}
