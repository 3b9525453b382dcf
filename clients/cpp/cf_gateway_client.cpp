// The C++ client of the Common Framework's gateway: see cf_gateway_client.hpp.
#include "cf_gateway_client.hpp"

#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <sstream>

namespace cf {

// ---- values ------------------------------------------------------------------------------------

Value Value::list(std::vector<Value> items) {
    Value v;
    v.kind = Kind::List;
    v.items = std::move(items);
    return v;
}

Value Value::string(std::string s) {
    Value v;
    v.kind = Kind::String;
    v.text = std::move(s);
    return v;
}

Value Value::symbol(std::string word) {
    Value v;
    v.kind = Kind::Symbol;
    v.text = std::move(word);
    return v;
}

std::string Value::head() const {
    if (kind == Kind::List && !items.empty() && items[0].kind == Kind::Symbol) return items[0].text;
    return "";
}

long long Value::as_integer() const {
    if (kind != Kind::Integer) throw std::invalid_argument("not an integer: " + text);
    return std::stoll(text);
}

double Value::as_double() const {
    if (kind != Kind::Integer && kind != Kind::Float) throw std::invalid_argument("not a number: " + text);
    return std::stod(text);
}

SyntaxError::SyntaxError(const std::string& why, int line_, int column_)
    : std::runtime_error(why + " at line " + std::to_string(line_) + ", column " + std::to_string(column_)),
      line(line_),
      column(column_) {}

// ---- the reader --------------------------------------------------------------------------------

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool ends_word(char c) { return is_space(c) || c == '(' || c == ')' || c == '"' || c == ';'; }

// integer = [+-] digit {digit}; float = [+-] (digits "." [digits] | "." digits | digits) [exponent],
// with a "." or an exponent.
Value::Kind number_kind(const std::string& w, bool* is_number) {
    std::size_t i = 0, n = w.size();
    if (i < n && (w[i] == '+' || w[i] == '-')) i++;
    std::size_t int_digits = 0, frac_digits = 0;
    while (i < n && is_digit(w[i])) i++, int_digits++;
    bool dot = false, exponent = false;
    if (i < n && w[i] == '.') {
        dot = true;
        i++;
        while (i < n && is_digit(w[i])) i++, frac_digits++;
    }
    if (int_digits + frac_digits == 0) {
        *is_number = false;
        return Value::Kind::Symbol;
    }
    if (i < n && (w[i] == 'e' || w[i] == 'E')) {
        std::size_t j = i + 1, exp_digits = 0;
        if (j < n && (w[j] == '+' || w[j] == '-')) j++;
        while (j < n && is_digit(w[j])) j++, exp_digits++;
        if (exp_digits == 0) {
            *is_number = false;
            return Value::Kind::Symbol;
        }
        exponent = true;
        i = j;
    }
    *is_number = i == n;
    return dot || exponent ? Value::Kind::Float : Value::Kind::Integer;
}

class Reader {
public:
    Reader(const std::string& text, const Limits& limits) : s_(text), limits_(limits) {}

    Value document() {
        if (s_.size() > limits_.max_bytes)
            throw SyntaxError("text longer than " + std::to_string(limits_.max_bytes) + " bytes", 1, 1);
        skip();
        if (pos_ >= s_.size()) fail("expected an expression, found end of input");
        Value v = item(0);
        skip();
        if (pos_ < s_.size()) fail(std::string("expected end of input, found '") + s_[pos_] + "'");
        return v;
    }

private:
    [[noreturn]] void fail(const std::string& why) const { fail_at(why, pos_); }

    [[noreturn]] void fail_at(const std::string& why, std::size_t at) const {
        int line = 1, column = 1;
        for (std::size_t i = 0; i < at && i < s_.size(); i++) {
            if (s_[i] == '\n') line++, column = 1;
            else if ((static_cast<unsigned char>(s_[i]) & 0xC0) != 0x80) column++;  // count characters
        }
        throw SyntaxError(why, line, column);
    }

    void skip() {
        while (pos_ < s_.size()) {
            if (is_space(s_[pos_])) {
                pos_++;
            } else if (s_[pos_] == ';') {
                while (pos_ < s_.size() && s_[pos_] != '\n') pos_++;
            } else {
                break;
            }
        }
    }

    void count_atom() {
        if (++atoms_ > limits_.max_atoms) fail("more than " + std::to_string(limits_.max_atoms) + " atoms");
    }

    Value item(int depth) {
        char c = s_[pos_];
        if (c == '(') return list(depth + 1);
        if (c == ')') fail("unexpected ')'");
        count_atom();
        if (c == '"') return string();
        return word();
    }

    Value list(int depth) {
        if (depth > limits_.max_depth) fail("nesting deeper than " + std::to_string(limits_.max_depth) + " levels");
        std::size_t open = pos_++;
        Value v = Value::list();
        while (true) {
            skip();
            if (pos_ >= s_.size()) fail_at("unclosed '(': expected ')', found end of input", open);
            if (s_[pos_] == ')') {
                pos_++;
                return v;
            }
            v.items.push_back(item(depth));
        }
    }

    Value string() {
        std::size_t open = pos_++;
        std::string out;
        while (true) {
            if (pos_ >= s_.size()) fail_at("unclosed string: expected '\"', found end of input", open);
            char c = s_[pos_++];
            if (c == '"') return Value::string(out);
            if (c != '\\') {
                out += c;
                continue;
            }
            if (pos_ >= s_.size()) fail_at("unclosed string: expected '\"', found end of input", open);
            char e = s_[pos_++];
            switch (e) {
                case '"': out += '"'; break;
                case '\\': out += '\\'; break;
                case 'n': out += '\n'; break;
                case 't': out += '\t'; break;
                case 'r': out += '\r'; break;
                default: fail_at(std::string("unknown escape '\\") + e + "' in a string", pos_ - 2);
            }
        }
    }

    Value word() {
        std::size_t start = pos_;
        while (pos_ < s_.size() && !ends_word(s_[pos_])) pos_++;
        std::string w = s_.substr(start, pos_ - start);
        Value v;
        v.text = w;
        if (w[0] == ':') {
            if (w.size() == 1 || w[1] == ':') fail_at("a keyword needs a name after ':'", start);
            v.kind = Value::Kind::Keyword;
            return v;
        }
        bool number = false;
        Value::Kind kind = number_kind(w, &number);
        if (!number) {
            v.kind = Value::Kind::Symbol;
            return v;
        }
        v.kind = kind;
        if (kind == Value::Kind::Integer) {
            std::size_t digits = w.size() - (w[0] == '+' || w[0] == '-' ? 1 : 0);
            if (digits > limits_.max_integer_digits)
                fail_at("integer longer than " + std::to_string(limits_.max_integer_digits) + " digits", start);
        } else {
            errno = 0;
            double d = std::strtod(w.c_str(), nullptr);
            if (errno == ERANGE && (d > 1.0 || d < -1.0)) fail_at("number out of range: " + w, start);
        }
        return v;
    }

    const std::string& s_;
    const Limits& limits_;
    std::size_t pos_ = 0;
    std::size_t atoms_ = 0;
};

}  // namespace

Value read(const std::string& text, const Limits& limits) { return Reader(text, limits).document(); }

std::string quote(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\t': out += "\\t"; break;
            case '\r': out += "\\r"; break;
            default: out += c;
        }
    }
    return out + "\"";
}

std::string write(const Value& v) {
    switch (v.kind) {
        case Value::Kind::String: return quote(v.text);
        case Value::Kind::List: {
            std::string out = "(";
            for (std::size_t i = 0; i < v.items.size(); i++) {
                if (i) out += ' ';
                out += write(v.items[i]);
            }
            return out + ")";
        }
        default: return v.text;
    }
}

const Value* param(const Value& list, const std::string& key) {
    if (!list.is_list()) return nullptr;
    for (std::size_t i = 1; i + 1 < list.items.size(); i++) {
        if (list.items[i].is(Value::Kind::Keyword, ":" + key)) return &list.items[i + 1];
    }
    return nullptr;
}

std::string text_of(const Value* value) {
    if (value == nullptr || value->is_list()) return "";
    return value->text;
}

// ---- the gateway -------------------------------------------------------------------------------

Gateway::Gateway(const std::string& host, int port, const std::string& name_, const std::string& token)
    : name(name_) {
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    addrinfo* found = nullptr;
    int rc = getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found);
    if (rc != 0) throw GatewayError("cannot resolve " + host + ": " + gai_strerror(rc));
    for (addrinfo* a = found; a != nullptr; a = a->ai_next) {
        fd_ = ::socket(a->ai_family, a->ai_socktype, a->ai_protocol);
        if (fd_ < 0) continue;
        if (::connect(fd_, a->ai_addr, a->ai_addrlen) == 0) break;
        ::close(fd_);
        fd_ = -1;
    }
    freeaddrinfo(found);
    if (fd_ < 0) throw GatewayError("cannot connect to " + host + ":" + std::to_string(port));
    command("(hello :name " + name + (token.empty() ? "" : " :token " + quote(token)) + ")", "welcome");
}

Gateway::~Gateway() {
    if (fd_ >= 0) ::close(fd_);
}

void Gateway::send_line(const std::string& line) {
    std::string data = line + "\n";
    std::size_t sent = 0;
    while (sent < data.size()) {
        ssize_t n = ::send(fd_, data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
        if (n < 0) {
            if (errno == EINTR) continue;
            throw GatewayError(std::string("cannot send to the gateway: ") + std::strerror(errno));
        }
        sent += static_cast<std::size_t>(n);
    }
}

Value Gateway::read_message(Deadline deadline) {
    while (true) {
        std::size_t end = buffer_.find('\n');
        if (end != std::string::npos) {
            std::string line = buffer_.substr(0, end);
            buffer_.erase(0, end + 1);
            if (!line.empty() && line.back() == '\r') line.pop_back();
            if (line.empty()) continue;
            return read(line);
        }
        if (deadline != Deadline::max()) {
            auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
            pollfd ready{fd_, POLLIN, 0};
            int got = left.count() > 0 ? ::poll(&ready, 1, static_cast<int>(left.count())) : 0;
            if (got < 0 && errno == EINTR) continue;
            if (got == 0) throw GatewayTimeout("nothing from the gateway in time");
        }
        char chunk[65536];
        ssize_t n = ::recv(fd_, chunk, sizeof chunk, 0);
        if (n == 0) throw GatewayError("the gateway closed the connection");
        if (n < 0) {
            if (errno == EINTR) continue;
            throw GatewayError(std::string("cannot read from the gateway: ") + std::strerror(errno));
        }
        buffer_.append(chunk, static_cast<std::size_t>(n));
    }
}

// The gateway's own failure, not-understood or error (it has no :sender) as a GatewayError.
static void throw_if_refused(const Value& msg) {
    std::string head = msg.head();
    if (param(msg, "sender") == nullptr && (head == "failure" || head == "not-understood" || head == "error"))
        throw GatewayError(head + ": " + text_of(param(msg, "reason")));
}

Value Gateway::command(const std::string& line, const std::string& expect) {
    send_line(line);
    while (true) {
        Value answer = read_message();
        throw_if_refused(answer);
        if (answer.head() == expect) return answer;
        if (param(answer, "sender") != nullptr) inbox_.push_back(std::move(answer));
    }
}

double Gateway::register_as(const std::string& service_class, const std::string& team, int player, double lease) {
    std::ostringstream line;
    line << "(register :service-class " << service_class;
    if (!team.empty()) line << " :team " << quote(team);
    if (player > 0) line << " :player " << player;
    line << " :lease " << lease << ")";
    Value answer = command(line.str(), "registered");
    const Value* granted = param(answer, "lease");
    return granted ? granted->as_double() : lease;
}

std::vector<std::string> Gateway::lookup(const std::string& service_class, const std::string& team) {
    std::string line = "(lookup :service-class " + service_class + (team.empty() ? "" : " :team " + quote(team)) + ")";
    Value answer = command(line, "providers");
    std::vector<std::string> names;
    if (answer.items.size() > 1 && answer.items[1].is_list()) {  // (providers (provider ...) ...)
        for (std::size_t i = 1; i < answer.items.size(); i++) names.push_back(text_of(param(answer.items[i], "name")));
    }
    return names;
}

Value Gateway::receive() { return receive(Deadline::max()); }

Value Gateway::receive(Deadline deadline) {
    if (!inbox_.empty()) {
        Value v = std::move(inbox_.front());
        inbox_.pop_front();
        return v;
    }
    while (true) {
        Value msg = read_message(deadline);
        if (param(msg, "sender") != nullptr) return msg;
        // What the gateway says itself is not ACL; but a failure may be about a message we
        // sent (an unknown receiver, say), and whoever waits for its answer must hear it.
        throw_if_refused(msg);
    }
}

// A FIPA date-time in UTC, to the millisecond: 20261125T101010123Z.
static std::string fipa_time(std::chrono::system_clock::time_point when) {
    auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(when.time_since_epoch()).count();
    std::time_t seconds = static_cast<std::time_t>(ms / 1000);
    std::tm utc{};
    gmtime_r(&seconds, &utc);
    char text[32];
    std::size_t n = std::strftime(text, sizeof text, "%Y%m%dT%H%M%S", &utc);
    std::snprintf(text + n, sizeof text - n, "%03dZ", static_cast<int>(ms % 1000));
    return text;
}

Value Gateway::request(const std::string& receiver, const std::string& content, double timeout) {
    std::string cid = name + "-c" + std::to_string(++conversations_);
    auto span = std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::duration<double>(timeout));
    // The wire carries the wall clock (the receiver's clock); our own wait is monotonic.
    Deadline deadline = std::chrono::steady_clock::now() + span;
    send_line("(request :receiver (set (agent-identifier :name " + receiver + ")) :content " + quote(content) +
              " :language cf-lang :ontology robocup-soccer :protocol fipa-request :conversation-id " + cid +
              " :reply-with " + cid + "-r1 :reply-by " + fipa_time(std::chrono::system_clock::now() + span) + ")");
    std::deque<Value> others;  // of other conversations: back to the inbox, in order, when this one ends
    auto put_back = [&] {
        for (auto it = others.rbegin(); it != others.rend(); ++it) inbox_.push_front(std::move(*it));
    };
    while (true) {
        Value msg;
        try {
            msg = receive(deadline);
        } catch (const GatewayTimeout&) {
            put_back();
            std::ostringstream why;
            why << "no answer from " << receiver << " within " << timeout << " s";
            throw GatewayTimeout(why.str());
        } catch (const GatewayError&) {
            put_back();
            throw;
        }
        if (text_of(param(msg, "conversation-id")) != cid) {
            others.push_back(std::move(msg));
            continue;
        }
        if (msg.head() == "agree") continue;
        put_back();
        return msg;
    }
}

void Gateway::reply(const Value& to, const std::string& performative, const std::string& content) {
    const Value* sender = param(to, "sender");
    std::string who = sender ? text_of(param(*sender, "name")) : "";
    std::string line = "(" + performative + " :receiver (set (agent-identifier :name " + who + "))";
    if (!content.empty()) line += " :content " + quote(content);
    std::string protocol = text_of(param(to, "protocol"));
    if (!protocol.empty()) line += " :protocol " + protocol;
    line += " :conversation-id " + text_of(param(to, "conversation-id"));
    std::string reply_with = text_of(param(to, "reply-with"));
    if (!reply_with.empty()) line += " :in-reply-to " + reply_with;
    send_line(line + ")");
}

void Gateway::close() {
    if (fd_ < 0) return;
    try {
        command("(bye)", "bye");
    } catch (const GatewayError&) {
        // closing anyway
    }
    ::close(fd_);
    fd_ = -1;
}

}  // namespace cf
