#include <osgLoA/util/AtomicFile>

#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/WriteFile>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <mutex>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace osgLoA
{
namespace
{
// ---------------------------------------------------------------- temporaries and signals

constexpr int kMaxTemporaries = 64;
constexpr std::size_t kMaxPath = 4096;

/** The registered temporary directories. Slots are claimed under the mutex; the signal handler
 *  reads them without it (a slot is marked in use only once its path is complete). */
struct Registry
{
    char paths[kMaxTemporaries][kMaxPath];
    std::atomic<bool> used[kMaxTemporaries];
    std::mutex mutex;
    bool handlersInstalled = false;
};

Registry& registry()
{
    static Registry* r = new Registry(); // never destroyed: handlers may run during exit
    return *r;
}

/** Removes the files in dir, then dir: async-signal-safe (open, getdents64, unlinkat, rmdir). */
void removeFlatDirectory(const char* dir)
{
    const int fd = ::open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0)
    {
        alignas(8) char buffer[8192];
        for (;;)
        {
            const long n = ::syscall(SYS_getdents64, fd, buffer, sizeof buffer);
            if (n <= 0) break;
            for (long off = 0; off < n;)
            {
                // struct linux_dirent64 { u64 d_ino; s64 d_off; u16 d_reclen; u8 d_type; char d_name[]; }
                unsigned short reclen = 0;
                std::memcpy(&reclen, buffer + off + 16, sizeof reclen);
                const char* name = buffer + off + 19;
                if (!(name[0] == '.' && (name[1] == 0 || (name[1] == '.' && name[2] == 0))))
                    ::unlinkat(fd, name, 0);
                off += reclen;
            }
        }
        ::close(fd);
    }
    ::rmdir(dir);
}

void onSignal(int sig)
{
    Registry& r = registry();
    // Newest first: a file's temporary inside a staging folder (AtomicDirectory) goes before it.
    for (int i = kMaxTemporaries - 1; i >= 0; --i)
        if (r.used[i].load()) removeFlatDirectory(r.paths[i]);
    ::signal(sig, SIG_DFL);
    ::raise(sig);
}

void installHandlers()
{
    for (int sig : {SIGINT, SIGTERM, SIGHUP})
    {
        struct sigaction old;
        if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) continue; // someone else's
        struct sigaction action;
        std::memset(&action, 0, sizeof action);
        action.sa_handler = onSignal;
        sigemptyset(&action.sa_mask);
        ::sigaction(sig, &action, nullptr);
    }
}

/** Unregisters and removes a temporary directory when it goes out of scope. */
struct TemporaryDirectory
{
    std::string path;
    explicit TemporaryDirectory(std::string p) : path(std::move(p)) { AtomicFile::registerTemporary(path); }
    ~TemporaryDirectory()
    {
        AtomicFile::removeTemporary(path);
        AtomicFile::unregisterTemporary(path);
    }
};

// ---------------------------------------------------------------- file system helpers

std::string errorText(int error)
{
    return std::strerror(error);
}

/** fsync of a file or directory; false with errno set on failure (EINVAL/EROFS of file systems
 *  that cannot sync are not failures). */
bool syncPath(const std::string& path, bool directory)
{
    const int fd = ::open(path.c_str(), (directory ? O_RDONLY | O_DIRECTORY : O_RDONLY) | O_CLOEXEC);
    if (fd < 0) return false;
    const bool ok = ::fsync(fd) == 0 || errno == EINVAL || errno == EROFS;
    const int saved = errno;
    ::close(fd);
    errno = saved;
    return ok;
}

/** Temporary directories of the same target left by processes that no longer run. */
void removeStaleTemporaries(const std::string& dir, const std::string& base)
{
    const std::string prefix = "." + base + ".tmp-";
    for (const std::string& f : osgDB::getDirectoryContents(dir))
    {
        if (f.compare(0, prefix.size(), prefix) != 0) continue;
        const std::string digits = f.substr(prefix.size());
        if (digits.empty() || digits.size() > 9 ||
            digits.find_first_not_of("0123456789") != std::string::npos)
            continue;
        const pid_t pid = static_cast<pid_t>(std::stol(digits));
        if (pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH)
            AtomicFile::removeTemporary(osgDB::concatPaths(dir, f));
    }
}

/** Copies the finished file into a device (no truncation, no replacement). */
void copyIntoDevice(const std::string& from, const std::string& device)
{
    std::ifstream in(from, std::ios::binary);
    const int fd = ::open(device.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) throw std::runtime_error("cannot write '" + device + "': " + errorText(errno));
    char buffer[65536];
    while (in)
    {
        in.read(buffer, sizeof buffer);
        std::streamsize n = in.gcount();
        const char* p = buffer;
        while (n > 0)
        {
            const ssize_t w = ::write(fd, p, static_cast<std::size_t>(n));
            if (w < 0 && errno == EINTR) continue;
            if (w <= 0)
            {
                const int error = w < 0 ? errno : ENOSPC;
                ::close(fd);
                throw std::runtime_error("cannot write '" + device + "': " + errorText(error));
            }
            p += w;
            n -= w;
        }
    }
    const bool synced = ::fsync(fd) == 0 || errno == EINVAL || errno == EROFS || errno == ENOTTY;
    const int error = errno;
    if (::close(fd) != 0 || !synced)
        throw std::runtime_error("cannot write '" + device + "': " + errorText(synced ? errno : error));
}
} // namespace

void AtomicFile::registerTemporary(const std::string& dir)
{
    if (dir.size() >= kMaxPath) return;
    Registry& r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    if (!r.handlersInstalled)
    {
        installHandlers();
        r.handlersInstalled = true;
    }
    // The slot after the highest one in use, so that a higher slot is always a newer temporary.
    int next = 0;
    for (int i = 0; i < kMaxTemporaries; ++i)
        if (r.used[i].load()) next = i + 1;
    if (next >= kMaxTemporaries) return;
    std::memcpy(r.paths[next], dir.c_str(), dir.size() + 1);
    r.used[next].store(true);
}

void AtomicFile::unregisterTemporary(const std::string& dir)
{
    Registry& r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    for (int i = 0; i < kMaxTemporaries; ++i)
        if (r.used[i].load() && dir == r.paths[i])
        {
            r.used[i].store(false);
            return;
        }
}

void AtomicFile::removeTemporary(const std::string& dir)
{
    removeFlatDirectory(dir.c_str());
}

AtomicFile::Target AtomicFile::resolve(const std::string& path)
{
    Target t;
    t.path = path;
    for (int hops = 0;; ++hops)
    {
        struct stat st;
        if (::lstat(t.path.c_str(), &st) != 0)
        {
            if (errno == ENOENT) return t; // a new file (a dangling link's target too)
            throw std::runtime_error("cannot write '" + path + "': " + errorText(errno));
        }
        if (S_ISLNK(st.st_mode))
        {
            if (hops >= 40)
                throw std::runtime_error("cannot write '" + path + "': too many levels of symbolic links");
            char buffer[kMaxPath];
            const ssize_t n = ::readlink(t.path.c_str(), buffer, sizeof buffer - 1);
            if (n < 0) throw std::runtime_error("cannot write '" + path + "': " + errorText(errno));
            const std::string link(buffer, static_cast<std::size_t>(n));
            const std::string dir = osgDB::getFilePath(t.path);
            t.path = (link[0] == '/' || dir.empty()) ? link : osgDB::concatPaths(dir, link);
            continue;
        }
        if (S_ISREG(st.st_mode))
            t.kind = REGULAR_FILE;
        else if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode))
            t.kind = DEVICE;
        else if (S_ISFIFO(st.st_mode))
            throw std::runtime_error("'" + path +
                                     "' is a FIFO: not written (a FIFO blocks until it is read)");
        else if (S_ISDIR(st.st_mode))
            throw std::runtime_error("'" + path + "' is a directory, not a file");
        else
            throw std::runtime_error("'" + path + "' is a socket or another special file: not written");
        return t;
    }
}

void AtomicFile::makeParentDirectories(const std::string& path)
{
    const std::string dir = osgDB::getFilePath(path);
    if (!dir.empty() && !osgDB::fileExists(dir) && !osgDB::makeDirectory(dir))
        throw std::runtime_error("cannot create directory '" + dir + "'");
}

void AtomicFile::write(const std::string& path, const std::function<bool(const std::string&)>& writer)
{
    const Target target = resolve(path);
    // The temporary lives beside the final target (a device's in the system's temporary folder);
    // the writer sees the name the caller gave (its extension chooses osgDB's writer).
    const std::string base = osgDB::getSimpleFileName(path);
    std::string dir;
    if (target.kind == DEVICE)
    {
        const char* tmp = std::getenv("TMPDIR");
        dir = tmp && *tmp ? tmp : "/tmp";
    }
    else
    {
        makeParentDirectories(target.path);
        dir = osgDB::getFilePath(target.path);
        if (dir.empty()) dir = ".";
        removeStaleTemporaries(dir, base);
    }
    const std::string tempDir = osgDB::concatPaths(dir, "." + base + ".tmp-" + std::to_string(::getpid()));
    removeTemporary(tempDir);
    if (::mkdir(tempDir.c_str(), 0700) != 0)
        throw std::runtime_error("cannot write '" + path +
                                 "': cannot create a temporary directory beside it (" + errorText(errno) +
                                 ")");
    TemporaryDirectory guard(tempDir);
    const std::string temp = osgDB::concatPaths(tempDir, base);
    if (!writer(temp) || !osgDB::fileExists(temp)) throw std::runtime_error("cannot write '" + path + "'");

    if (target.kind == DEVICE)
    {
        copyIntoDevice(temp, target.path);
        return;
    }
    // Flush every file, keep an existing file's permissions (and owner, as root), then move the
    // side files and the main file into place and flush the directory.
    for (const std::string& f : osgDB::getDirectoryContents(tempDir))
        if (f != "." && f != ".." && !syncPath(osgDB::concatPaths(tempDir, f), false))
            throw std::runtime_error("cannot write '" + path + "': " + errorText(errno));
    struct stat old;
    if (target.kind == REGULAR_FILE && ::stat(target.path.c_str(), &old) == 0)
    {
        ::chmod(temp.c_str(), old.st_mode & 07777);
        if (::geteuid() == 0 && ::chown(temp.c_str(), old.st_uid, old.st_gid) != 0)
        {
            // not fatal: the file is written, with root's ownership
        }
    }
    const std::string targetDir = osgDB::getFilePath(target.path);
    const auto move = [&](const std::string& from, const std::string& to)
    {
        if (std::rename(from.c_str(), to.c_str()) != 0)
            throw std::runtime_error("cannot rename a temporary file onto '" + to + "': " + errorText(errno));
    };
    for (const std::string& f : osgDB::getDirectoryContents(tempDir))
        if (f != "." && f != ".." && f != base)
            move(osgDB::concatPaths(tempDir, f), targetDir.empty() ? f : osgDB::concatPaths(targetDir, f));
    move(temp, target.path);
    syncPath(targetDir.empty() ? "." : targetDir, true);
}

void AtomicFile::writeText(const std::string& path, const std::string& text)
{
    write(path,
          [&](const std::string& temp)
          {
              std::ofstream out(temp, std::ios::binary | std::ios::trunc);
              out << text;
              out.close();
              return static_cast<bool>(out);
          });
}

void AtomicFile::writeNode(const std::string& path, const osg::Node& node, const osgDB::Options* options)
{
    write(path, [&](const std::string& temp) { return osgDB::writeNodeFile(node, temp, options); });
}

} // namespace osgLoA
