#include <osgLoA/util/AtomicDirectory>
#include <osgLoA/util/AtomicFile>

#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <linux/fs.h>
#include <sys/stat.h>
#include <unistd.h>

namespace osgLoA
{

AtomicDirectory::AtomicDirectory(const std::string& directory, const std::string& marker)
    : _directory(directory)
{
    while (_directory.size() > 1 && _directory.back() == '/')
        _directory.pop_back();
    if (_directory.empty()) throw std::runtime_error("no output folder given");
    struct stat st;
    if (::stat(_directory.c_str(), &st) == 0)
    {
        if (!S_ISDIR(st.st_mode))
            throw std::runtime_error("'" + _directory + "' exists and is not a directory");
        std::string stranger;
        for (const std::string& f : osgDB::getDirectoryContents(_directory))
            if (f != "." && f != ".." && stranger.empty()) stranger = f;
        if (!stranger.empty() && !osgDB::fileExists(osgDB::concatPaths(_directory, marker)))
            throw std::runtime_error("'" + _directory + "' holds files this tool did not write ('" +
                                     stranger + "', and no " + marker + "): give an empty or new folder");
    }
    const std::string parent = osgDB::getFilePath(_directory);
    if (!parent.empty()) AtomicFile::makeParentDirectories(_directory);
    _staging = osgDB::concatPaths(parent.empty() ? "." : parent, "." + osgDB::getSimpleFileName(_directory) +
                                                                     ".tmp-" + std::to_string(::getpid()));
    AtomicFile::removeTemporary(_staging);
    if (::mkdir(_staging.c_str(), 0777) != 0)
        throw std::runtime_error("cannot create the output directory '" + _directory +
                                 "' (a staging folder beside it: " + std::strerror(errno) + ")");
    AtomicFile::registerTemporary(_staging);
}

AtomicDirectory::~AtomicDirectory()
{
    if (!_committed) AtomicFile::removeTemporary(_staging);
    AtomicFile::unregisterTemporary(_staging);
}

void AtomicDirectory::commit()
{
    if (_committed) return;
    struct stat st;
    if (::stat(_directory.c_str(), &st) != 0)
    {
        if (std::rename(_staging.c_str(), _directory.c_str()) != 0)
            throw std::runtime_error("cannot move the new outputs into '" + _directory +
                                     "': " + std::strerror(errno));
        _committed = true;
        return;
    }
    // Both exist: the new folder takes the old one's permissions; exchange them in one step, then
    // remove the old contents (now in _staging).
    ::chmod(_staging.c_str(), st.st_mode & 07777);
    if (::renameat2(AT_FDCWD, _staging.c_str(), AT_FDCWD, _directory.c_str(), RENAME_EXCHANGE) != 0)
    {
        // A file system without RENAME_EXCHANGE: the old folder aside, the new one in, in two steps.
        const std::string aside = _staging + "-old";
        AtomicFile::removeTemporary(aside);
        if (std::rename(_directory.c_str(), aside.c_str()) != 0 ||
            std::rename(_staging.c_str(), _directory.c_str()) != 0)
            throw std::runtime_error("cannot move the new outputs into '" + _directory +
                                     "': " + std::strerror(errno));
        AtomicFile::removeTemporary(aside);
        _committed = true;
        return;
    }
    AtomicFile::removeTemporary(_staging);
    _committed = true;
}

} // namespace osgLoA
