/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#ifndef OSGLOA_PLUGINS_CITYJSON_INDEXEDORDEREDMAP_H
#define OSGLOA_PLUGINS_CITYJSON_INDEXEDORDEREDMAP_H 1

#include <nlohmann/json.hpp>

#include <cstddef>
#include <functional>
#include <memory>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace loacityjson
{

/** nlohmann::ordered_map (a JSON object that keeps its keys in file order, so city objects are
 *  read in the order the file lists them) with a hash index over its keys. ordered_map finds a
 *  key by walking its entries, and the parser looks up every key it adds: an object of n keys
 *  took n^2/2 comparisons to read ("CityObjects" with 20,000 entries: 2e8, seconds under
 *  AddressSanitizer; a city tile of 200,000 would take minutes). Here lookups are hashed.
 *
 *  The index covers positions [0, _indexed); entries appended by ordered_map's own members are
 *  indexed on the next lookup, and any erase drops the index (rebuilt on the next lookup). */
template <class Key, class T, class IgnoredLess = std::less<Key>,
          class Allocator = std::allocator<std::pair<const Key, T>>>
struct IndexedOrderedMap : nlohmann::ordered_map<Key, T, IgnoredLess, Allocator>
{
    using Base = nlohmann::ordered_map<Key, T, IgnoredLess, Allocator>;
    using typename Base::const_iterator;
    using typename Base::iterator;
    using typename Base::key_type;
    using typename Base::size_type;
    using typename Base::value_type;

    IndexedOrderedMap() = default;
    explicit IndexedOrderedMap(const Allocator& alloc) : Base(alloc) {}
    template <class It>
    IndexedOrderedMap(It first, It last, const Allocator& alloc = Allocator()) : Base(first, last, alloc)
    {
    }
    IndexedOrderedMap(std::initializer_list<value_type> init, const Allocator& alloc = Allocator())
        : Base(init, alloc)
    {
    }

    std::pair<iterator, bool> emplace(const key_type& key, T&& t)
    {
        const iterator found = find(key);
        if (found != this->end()) return {found, false};
        this->emplace_back(key, std::move(t));
        return {std::prev(this->end()), true};
    }
    T& operator[](const key_type& key) { return emplace(key, T{}).first->second; }
    const T& operator[](const key_type& key) const { return at(key); }

    iterator find(const key_type& key)
    {
        const std::size_t i = position(key);
        return i == npos ? this->end() : this->begin() + static_cast<std::ptrdiff_t>(i);
    }
    const_iterator find(const key_type& key) const
    {
        const std::size_t i = position(key);
        return i == npos ? this->end() : this->begin() + static_cast<std::ptrdiff_t>(i);
    }
    T& at(const key_type& key)
    {
        const iterator found = find(key);
        if (found == this->end()) throw std::out_of_range("key not found");
        return found->second;
    }
    const T& at(const key_type& key) const
    {
        const const_iterator found = find(key);
        if (found == this->end()) throw std::out_of_range("key not found");
        return found->second;
    }
    size_type count(const key_type& key) const { return position(key) == npos ? 0 : 1; }

    template <class... Args> decltype(auto) erase(Args&&... args)
    {
        _index.clear();
        _indexed = 0;
        return Base::erase(std::forward<Args>(args)...);
    }

private:
    static constexpr std::size_t npos = ~std::size_t(0);
    mutable std::unordered_map<Key, std::size_t> _index;
    mutable std::size_t _indexed = 0;

    std::size_t position(const key_type& key) const
    {
        if (_indexed > this->size())
        {
            _index.clear();
            _indexed = 0;
        }
        for (; _indexed < this->size(); ++_indexed)
            _index.emplace((this->begin() + static_cast<std::ptrdiff_t>(_indexed))->first,
                           _indexed); // the first of a duplicate wins, as in ordered_map
        const auto found = _index.find(key);
        return found == _index.end() ? npos : found->second;
    }
};

/** A CityJSON document: JSON objects in file order, with hashed key lookup. */
using Json = nlohmann::basic_json<IndexedOrderedMap>;

} // namespace loacityjson

#endif
