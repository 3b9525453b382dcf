// A Common Framework agent in C++17 over the TCP gateway: standard library and POSIX sockets only.
//
// Two parts, both in namespace cf:
//   - the S-expression reader and writer of the Framework Language (docs/language.md, section 1):
//     cf::read(text) -> cf::Value, cf::write(value), cf::quote(string);
//   - cf::Gateway: one connection to the gateway (docs/gateway-protocol.md): hello, register,
//     lookup, send and receive ACL messages, run a fipa-request, answer one, bye.
//
// Drop cf_gateway_client.hpp and cf_gateway_client.cpp into your build (or add_subdirectory this
// folder and link cf_gateway_client). example.cpp is a complete agent.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <stdexcept>
#include <string>
#include <vector>

namespace cf {

// ---- the language: S-expressions ------------------------------------------------------------

struct Value {
    enum class Kind { List, String, Integer, Float, Symbol, Keyword };
    Kind kind = Kind::List;
    std::string text;          // the string's characters, the word, or the number as written
    std::vector<Value> items;  // a list's items

    static Value list(std::vector<Value> items = {});
    static Value string(std::string s);
    static Value symbol(std::string word);

    bool is_list() const { return kind == Kind::List; }
    bool is(Kind k, const std::string& t) const { return kind == k && text == t; }
    // The first item of a list when it is a symbol (a message's performative, an instance's class).
    std::string head() const;
    // A number's value; std::invalid_argument if this is not a number (or does not fit).
    long long as_integer() const;
    double as_double() const;
};

// Limits of the reader (docs/language.md: a reader may be stricter, never looser).
struct Limits {
    std::size_t max_bytes = 1 << 20;
    int max_depth = 64;
    std::size_t max_atoms = 100000;
    std::size_t max_integer_digits = 4000;
};

// A syntax error: where (1-based line and column) and why.
struct SyntaxError : std::runtime_error {
    int line, column;
    SyntaxError(const std::string& why, int line, int column);
};

// One expression (and nothing but space and comments around it).
Value read(const std::string& text, const Limits& limits = Limits());
// The expression as one line of text, strings escaped.
std::string write(const Value& value);
// A string literal: "...", with \" \\ \n \t \r escaped.
std::string quote(const std::string& s);
// In a list such as (head :key value ...), the value after :key; nullptr if absent.
const Value* param(const Value& list, const std::string& key);
// A string's characters or an atom's text; "" for nullptr or a list.
std::string text_of(const Value* value);

// ---- the gateway -------------------------------------------------------------------------------

struct GatewayError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Nothing came by a deadline (a request's reply-by).
struct GatewayTimeout : GatewayError {
    using GatewayError::GatewayError;
};

class Gateway {
public:
    // Connects and says hello (with the token if the gateway requires one).
    Gateway(const std::string& host, int port, const std::string& name, const std::string& token = "");
    ~Gateway();
    Gateway(const Gateway&) = delete;
    Gateway& operator=(const Gateway&) = delete;

    const std::string name;

    void send_line(const std::string& line);
    // Sends a command; returns the gateway's answer headed `expect`. ACL messages that arrive
    // meanwhile are kept for receive(); a failure/error answer throws GatewayError.
    Value command(const std::string& line, const std::string& expect);
    // Registers this agent; returns the lease the ComMAg granted.
    double register_as(const std::string& service_class, const std::string& team = "", int player = 0,
                       double lease = 2.0);
    // Providers' names, best first.
    std::vector<std::string> lookup(const std::string& service_class, const std::string& team = "");
    // The next ACL message addressed to us (blocks). A failure the gateway answers itself (to a
    // message we sent: an unknown receiver, say) throws GatewayError.
    Value receive();
    // A fipa-request to its final answer (inform, failure, refuse, ...); an agree is skipped.
    // The request carries :reply-by now + timeout (wall clock); with no answer by then,
    // GatewayTimeout. Messages of other conversations that arrive meanwhile are kept.
    Value request(const std::string& receiver, const std::string& content, double timeout = 30.0);
    // Answers a message of a conversation someone opened with us (agree, inform, failure, ...).
    void reply(const Value& to, const std::string& performative, const std::string& content = "");
    // Says bye (the gateway deregisters us) and closes.
    void close();

private:
    using Deadline = std::chrono::steady_clock::time_point;
    // The next line read as a value; GatewayTimeout if none arrives by `deadline`.
    Value read_message(Deadline deadline = Deadline::max());
    Value receive(Deadline deadline);
    int fd_ = -1;
    std::string buffer_;
    std::deque<Value> inbox_;
    int conversations_ = 0;
};

}  // namespace cf
