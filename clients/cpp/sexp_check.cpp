// Reads S-expressions with cf::read and prints what it read, one line per input, so that a test can
// compare this reader with the reference one (cf_lang) on the same texts.
//
// Input: texts separated by NUL bytes on stdin. Output per text: "OK <form>" or "ERROR <line>:<column> <why>",
// where <form> writes lists as (...), strings as S:"...", integers as I:<digits>, floats as F:<%.17g>,
// symbols as Y:<word> and keywords as K:<name>.
#include <cstdio>
#include <iostream>
#include <iterator>
#include <string>

#include "cf_gateway_client.hpp"

static std::string integer(const std::string& text) {
    std::size_t i = 0;
    bool negative = false;
    if (text[0] == '+' || text[0] == '-') negative = text[0] == '-', i = 1;
    while (i + 1 < text.size() && text[i] == '0') i++;
    std::string digits = text.substr(i);
    return (negative && digits != "0" ? "-" : "") + digits;
}

static std::string form(const cf::Value& v) {
    using K = cf::Value::Kind;
    switch (v.kind) {
        case K::List: {
            std::string out = "(";
            for (std::size_t i = 0; i < v.items.size(); i++) out += (i ? " " : "") + form(v.items[i]);
            return out + ")";
        }
        case K::String: return "S:" + cf::quote(v.text);
        case K::Integer: return "I:" + integer(v.text);
        case K::Float: {
            char buf[64];
            std::snprintf(buf, sizeof buf, "%.17g", v.as_double());
            return std::string("F:") + buf;
        }
        case K::Symbol: return "Y:" + v.text;
        case K::Keyword: return "K:" + v.text.substr(1);
    }
    return "?";
}

int main() {
    std::string all((std::istreambuf_iterator<char>(std::cin)), std::istreambuf_iterator<char>());
    std::size_t start = 0;
    while (start <= all.size()) {
        std::size_t end = all.find('\0', start);
        if (end == std::string::npos) end = all.size();
        std::string text = all.substr(start, end - start);
        try {
            std::string read = form(cf::read(text));
            std::cout << "OK " << read << "\n";
        } catch (const cf::SyntaxError& e) {
            std::string why = e.what();
            for (char& c : why)
                if (c == '\n' || c == '\r') c = ' ';  // one line per text
            std::cout << "ERROR " << e.line << ":" << e.column << " " << why << "\n";
        }
        if (end == all.size()) break;
        start = end + 1;
    }
    return 0;
}
