#include <osgLoA/util/AtomicFile>

#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/WriteFile>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <unistd.h>

namespace osgLoA
{
namespace
{
void removeTree(const std::string& dir)
{
    for (const std::string& f : osgDB::getDirectoryContents(dir))
        if (f != "." && f != "..") std::remove(osgDB::concatPaths(dir, f).c_str());
    ::rmdir(dir.c_str());
}
} // namespace

void AtomicFile::makeParentDirectories(const std::string& path)
{
    const std::string dir = osgDB::getFilePath(path);
    if (!dir.empty() && !osgDB::fileExists(dir) && !osgDB::makeDirectory(dir))
        throw std::runtime_error("cannot create directory '" + dir + "'");
}

void AtomicFile::write(const std::string& path, const std::function<bool(const std::string&)>& writer)
{
    makeParentDirectories(path);
    const std::string dir = osgDB::getFilePath(path);
    const std::string base = osgDB::getSimpleFileName(path);
    const std::string tempDir =
        osgDB::concatPaths(dir.empty() ? "." : dir, "." + base + ".tmp-" + std::to_string(::getpid()));
    removeTree(tempDir);
    if (!osgDB::makeDirectory(tempDir))
        throw std::runtime_error("cannot write '" + path +
                                 "': cannot create a temporary directory beside it");
    const std::string temp = osgDB::concatPaths(tempDir, base);
    bool ok = false;
    try
    {
        ok = writer(temp);
    }
    catch (...)
    {
        removeTree(tempDir);
        throw;
    }
    if (!ok || !osgDB::fileExists(temp))
    {
        removeTree(tempDir);
        throw std::runtime_error("cannot write '" + path + "'");
    }
    auto move = [&](const std::string& name)
    {
        const std::string from = osgDB::concatPaths(tempDir, name);
        const std::string to = dir.empty() ? name : osgDB::concatPaths(dir, name);
        if (std::rename(from.c_str(), to.c_str()) != 0)
        {
            const std::string why = std::strerror(errno);
            removeTree(tempDir);
            throw std::runtime_error("cannot rename a temporary file onto '" + to + "': " + why);
        }
    };
    for (const std::string& f : osgDB::getDirectoryContents(tempDir))
        if (f != "." && f != ".." && f != base) move(f);
    move(base);
    removeTree(tempDir);
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
