// A main() for the fuzz targets without libFuzzer: runs LLVMFuzzerTestOneInput once on each
// file named on the command line (a folder: each file in it, sorted), as libFuzzer replays
// inputs. CTest builds every target with it in the normal build and replays the seed corpora and
// the reproducers of tests/fuzz/ through it (FuzzReplay.*), so each input that once crashed,
// hung or blew up stays a regression test. Exit 0 when every input ran; a failure aborts (the
// target's own checks) or crashes, naming the input first. Each input must finish within
// --seconds-per-input (default 10), like scripts/fuzz's -timeout.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <dirent.h>
#include <sys/stat.h>

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv);
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace
{
bool isDirectory(const std::string& path)
{
    struct stat st;
    return ::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

void collect(const std::string& path, std::vector<std::string>& files)
{
    if (!isDirectory(path))
    {
        files.push_back(path);
        return;
    }
    std::vector<std::string> inside;
    if (DIR* d = ::opendir(path.c_str()))
    {
        while (dirent* e = ::readdir(d))
            if (e->d_name[0] != '.') inside.push_back(path + "/" + e->d_name);
        ::closedir(d);
    }
    std::sort(inside.begin(), inside.end());
    for (const std::string& f : inside)
        if (f.size() < 3 || f.compare(f.size() - 3, 3, ".md") != 0) collect(f, files); // READMEs are notes
}
} // namespace

int main(int argc, char** argv)
{
    double limit = 10.0;
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i)
    {
        if (std::strcmp(argv[i], "--seconds-per-input") == 0 && i + 1 < argc)
            limit = std::atof(argv[++i]);
        else
            collect(argv[i], files);
    }
    if (files.empty())
    {
        std::fprintf(stderr, "usage: %s [--seconds-per-input S] INPUT|FOLDER...\n", argv[0]);
        return 2;
    }
    LLVMFuzzerInitialize(&argc, &argv);
    int slow = 0;
    for (const std::string& f : files)
    {
        std::ifstream in(f.c_str(), std::ios::binary);
        if (!in)
        {
            std::fprintf(stderr, "cannot read %s\n", f.c_str());
            return 2;
        }
        std::ostringstream bytes;
        bytes << in.rdbuf();
        const std::string data = bytes.str();
        std::fprintf(stderr, "replay: %s (%zu bytes)\n", f.c_str(), data.size());
        const auto t0 = std::chrono::steady_clock::now();
        LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(data.data()), data.size());
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (s > limit)
        {
            std::fprintf(stderr, "replay: %s took %.2f s (limit %.1f s)\n", f.c_str(), s, limit);
            ++slow;
        }
    }
    std::fprintf(stderr, "replay: %zu inputs, %d over the time limit\n", files.size(), slow);
    return slow ? 1 : 0;
}
