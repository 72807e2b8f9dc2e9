// loa-scenario-parse: the helper program libosgLoA runs to parse a text scenario file (.osgt,
// .osgx) out of process (ScenarioLibrary::readData), because OSG 3.6.5's text readers can loop
// forever or crash on malformed input; the library gives it a deadline and kills it after that.
//
//   loa-scenario-parse [--label NAME] [FILE | -]
//
// Reads the text from FILE (or from stdin) and writes one reply on stdout: "S" followed by the
// scenario in OSG's binary format, or "E" followed by the error message, which names NAME (by
// default FILE, or "<stdin>"). Exits 0 once the reply is written.
#include <osgLoA/transitions/ScenarioTextParser.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

namespace
{
const char* kUsage = "usage: loa-scenario-parse [--label NAME] [FILE | -]\n"
                     "Parses a text scenario file (.osgt, .osgx) from FILE or stdin and writes the reply of\n"
                     "ScenarioLibrary::readData on stdout: 'S' + the scenario in OSG's binary format, or\n"
                     "'E' + the error message. libosgLoA runs it; it is no tool for people.\n";

bool readAll(int fd, std::string& text)
{
    char buffer[65536];
    for (;;)
    {
        const ssize_t n = read(fd, buffer, sizeof(buffer));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return false;
        if (n == 0) return true;
        text.append(buffer, std::size_t(n));
    }
}

bool writeAll(int fd, const std::string& bytes)
{
    std::size_t done = 0;
    while (done < bytes.size())
    {
        const ssize_t n = write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        done += std::size_t(n);
    }
    return true;
}
} // namespace

int main(int argc, char** argv)
{
    std::string label, file;
    for (int i = 1; i < argc; ++i)
    {
        const std::string a = argv[i];
        if (a == "--label" && i + 1 < argc)
            label = argv[++i];
        else if (a == "-h" || a == "--help")
        {
            std::fputs(kUsage, stdout);
            return 0;
        }
        else if (file.empty() && (a == "-" || a.compare(0, 1, "-") != 0))
            file = a;
        else
        {
            std::fputs(kUsage, stderr);
            return 2;
        }
    }
    const bool fromStdin = file.empty() || file == "-";
    if (label.empty()) label = fromStdin ? "<stdin>" : file;

    // The reply gets its own descriptor; whatever OSG prints (its notices go to stdout) goes to
    // stderr, so it cannot corrupt the reply.
    const int replyFd = dup(STDOUT_FILENO);
    if (replyFd < 0 || dup2(STDERR_FILENO, STDOUT_FILENO) < 0)
    {
        std::fprintf(stderr, "loa-scenario-parse: cannot set up stdout: %s\n", std::strerror(errno));
        return 1;
    }

    std::string text;
    std::string reply;
    if (fromStdin)
    {
        if (!readAll(STDIN_FILENO, text)) reply = "Ecannot read scenario file '" + label + "' from stdin";
    }
    else
    {
        std::ifstream in(file.c_str(), std::ios::binary);
        std::ostringstream s;
        s << in.rdbuf();
        if (!in) reply = "Ecannot read scenario file '" + label + "'";
        text = s.str();
    }
    if (reply.empty()) reply = osgLoA::detail::parseTextScenario(text, label);
    if (!writeAll(replyFd, reply)) return 1;
    close(replyFd);
    return 0;
}
