#include <osgLoA/util/MachineInfo>

#include <cmath>
#include <fstream>
#include <sstream>
#include <thread>

namespace osgLoA
{
namespace
{
std::string trim(std::string s)
{
    const auto b = s.find_first_not_of(" \t\"");
    const auto e = s.find_last_not_of(" \t\"\r\n");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}
} // namespace

MachineInfo MachineInfo::query()
{
    MachineInfo m;
    std::ifstream cpu("/proc/cpuinfo");
    for (std::string l; std::getline(cpu, l);)
        if (l.rfind("model name", 0) == 0 && l.find(':') != std::string::npos)
        {
            m.cpuModel = trim(l.substr(l.find(':') + 1));
            break;
        }
    if (m.cpuModel.empty()) m.cpuModel = "unknown CPU";
    m.cores = std::thread::hardware_concurrency();
    std::ifstream mem("/proc/meminfo");
    for (std::string l; std::getline(mem, l);)
        if (l.rfind("MemTotal:", 0) == 0)
        {
            std::istringstream in(l.substr(9));
            double kb = 0;
            in >> kb;
            m.memoryGiB = std::round(kb / (1024.0 * 1024.0) * 10.0) / 10.0;
        }
    std::ifstream os("/etc/os-release");
    for (std::string l; std::getline(os, l);)
        if (l.rfind("PRETTY_NAME=", 0) == 0) m.os = trim(l.substr(12));
    return m;
}

std::string MachineInfo::line(const std::string& glRenderer) const
{
    std::ostringstream o;
    o << cpuModel << ", " << cores << " cores, " << memoryGiB << " GiB, " << (os.empty() ? "unknown OS" : os);
    if (!glRenderer.empty()) o << "; GL: " << glRenderer;
    return o.str();
}

} // namespace osgLoA
