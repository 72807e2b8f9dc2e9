/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/FilterChain>
#include <osgLoA/filtering/FilterRegistry>

#include <map>
#include <mutex>
#include <stdexcept>

namespace osgLoA
{

namespace
{
struct Registered
{
    std::string description;
    FilterRegistry::Factory factory;
};
std::map<std::string, Registered>& table()
{
    static std::map<std::string, Registered> t;
    return t;
}
std::mutex& tableMutex()
{
    static std::mutex m;
    return m;
}

std::string trim(const std::string& s)
{
    const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

osg::ref_ptr<ImageFilter> createOne(const std::string& spec)
{
    const std::string::size_type colon = spec.find(':');
    const std::string name = trim(spec.substr(0, colon));
    FilterRegistry::Factory factory;
    {
        std::lock_guard<std::mutex> lock(tableMutex());
        auto it = table().find(name);
        if (it != table().end()) factory = it->second.factory;
    }
    if (!factory)
    {
        std::string known;
        for (const std::string& n : FilterRegistry::names())
            known += (known.empty() ? "" : ", ") + n;
        throw std::invalid_argument("unknown filter '" + name + "' (known: " + known + ")");
    }
    osg::ref_ptr<ImageFilter> f = factory();
    if (colon == std::string::npos) return f;
    const std::string params = spec.substr(colon + 1);
    std::string::size_type start = 0;
    while (start <= params.size())
    {
        const std::string::size_type comma = params.find(',', start);
        const std::string item =
            trim(params.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        if (!item.empty())
        {
            const std::string::size_type eq = item.find('=');
            if (eq == std::string::npos)
                throw std::invalid_argument(name + ": parameter '" + item +
                                            "' has no value (write key=value)");
            f->setParameter(trim(item.substr(0, eq)), trim(item.substr(eq + 1)));
        }
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return f;
}
} // namespace

void FilterRegistry::add(const std::string& name, const std::string& description, Factory factory)
{
    std::lock_guard<std::mutex> lock(tableMutex());
    table()[name] = Registered{description, std::move(factory)};
}

std::vector<std::string> FilterRegistry::names()
{
    std::lock_guard<std::mutex> lock(tableMutex());
    std::vector<std::string> n;
    for (const auto& e : table())
        n.push_back(e.first);
    return n;
}

std::string FilterRegistry::description(const std::string& name)
{
    std::lock_guard<std::mutex> lock(tableMutex());
    auto it = table().find(name);
    return it == table().end() ? std::string() : it->second.description;
}

osg::ref_ptr<ImageFilter> FilterRegistry::create(const std::string& specification)
{
    if (trim(specification).empty()) throw std::invalid_argument("empty filter specification");
    std::vector<std::string> parts;
    std::string::size_type start = 0;
    for (;;)
    {
        const std::string::size_type plus = specification.find('+', start);
        parts.push_back(
            specification.substr(start, plus == std::string::npos ? std::string::npos : plus - start));
        if (plus == std::string::npos) break;
        start = plus + 1;
    }
    if (parts.size() == 1) return createOne(parts[0]);
    osg::ref_ptr<FilterChain> chain = new FilterChain;
    for (const std::string& p : parts)
        chain->addFilter(createOne(p).get());
    return chain;
}

} // namespace osgLoA
