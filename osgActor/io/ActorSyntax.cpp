#include <osgActor/io/ActorLexer>
#include <osgActor/io/ActorSyntax>
#include <osgActor/io/SyntaxWriter>

#include <algorithm>
#include <iterator>

namespace osgActor {

namespace {

/** Deeper nesting than this is refused rather than risking the stack on a hostile file. */
constexpr unsigned kMaxDepth = 200;
/** Blocks of at most this many statements are copied out of the parser's scratch list at their exact size. */
constexpr std::size_t kSmallBlock = 32;

/** One parse of one stream: the lexer, one token of look-ahead and the first error. */
class SyntaxParser
{
public:
    SyntaxParser(TextLines& text, const std::string& fileName)
        : _lexer(text), _fileName(fileName), _blocks(kMaxDepth + 1)
    {
        advance();
    }

    /** Statements up to the end of the file (depth 0) or to the brace that closes the current block. They are
      * gathered in the depth's scratch list, whose room is kept from block to block, and a small block's are then
      * moved into a list of their exact size: a file of many small blocks (a joint each) does not grow every
      * block's list a statement at a time. A large block takes the scratch list itself (moving its statements once
      * more would cost more than the allocations it saves). */
    bool parseStatements(std::vector<SyntaxStatement>& statements, unsigned depth, int openLine)
    {
        std::vector<SyntaxStatement>& gathered = _blocks[depth];
        gathered.clear();
        if (!gatherStatements(gathered, depth, openLine)) return false;
        if (gathered.size() > kSmallBlock)
        {
            statements.swap(gathered);
            return true;
        }
        statements.reserve(gathered.size());
        std::move(gathered.begin(), gathered.end(), std::back_inserter(statements));
        gathered.clear();
        return true;
    }

    const std::string& error() const { return _error; }

private:
    bool gatherStatements(std::vector<SyntaxStatement>& statements, unsigned depth, int openLine)
    {
        for (;;)
        {
            switch (_token.type)
            {
            case TokenType::EndOfStatement: advance(); break;
            case TokenType::EndOfFile:
                if (depth == 0) return true;
                return fail(_token.line, "the file ends inside the block opened at line " + std::to_string(openLine));
            case TokenType::CloseBrace:
                if (depth == 0) return fail(_token.line, "'}' closes no block");
                advance();
                return true;
            case TokenType::Error: return fail(_token.line, _token.text);
            case TokenType::Word:
            {
                statements.emplace_back();
                if (!parseStatement(statements.back(), depth)) return false;
                break;
            }
            case TokenType::String:
                return fail(_token.line,
                            "a statement must start with a keyword, not the string \"" + _token.text + "\"");
            case TokenType::OpenBrace: return fail(_token.line, "'{' must follow a keyword");
            }
        }
    }

    bool parseStatement(SyntaxStatement& statement, unsigned depth)
    {
        statement.keyword = std::move(_token.text);
        statement.line = _token.line;
        advance();
        // Gathered first, then moved in at their final size (one allocation, not one per doubling).
        _arguments.clear();
        while (_token.type == TokenType::Word || _token.type == TokenType::String)
        {
            _arguments.push_back(SyntaxArgument{std::move(_token.text), _token.type == TokenType::String, _token.line});
            advance();
        }
        statement.arguments.assign(std::make_move_iterator(_arguments.begin()),
                                   std::make_move_iterator(_arguments.end()));
        if (_token.type == TokenType::Error) return fail(_token.line, _token.text);
        if (_token.type != TokenType::OpenBrace) return true; // a newline, ';', '}' or the end of the file ends it
        if (depth + 1 > kMaxDepth) return fail(_token.line, "blocks are nested too deeply");
        const int openLine = _token.line;
        advance();
        statement.hasBlock = true;
        return parseStatements(statement.children, depth + 1, openLine);
    }

    void advance() { _token = _lexer.next(); }

    bool fail(int line, const std::string& message)
    {
        _error = _fileName + ":" + std::to_string(line) + ": " + message;
        return false;
    }

    ActorLexer _lexer;
    const std::string& _fileName;
    Token _token;
    std::string _error;
    std::vector<std::vector<SyntaxStatement>> _blocks; // per depth, the statements of the block being parsed
    std::vector<SyntaxArgument> _arguments;            // the arguments of the statement being parsed
};

} // namespace

bool needsQuotes(std::string_view name)
{
    if (name.empty()) return true;
    for (const char c : name)
    {
        const unsigned char u = static_cast<unsigned char>(c);
        if (u <= ' ' || u == 127 || c == '{' || c == '}' || c == ';' || c == '#' || c == '"' || c == '\\')
            return true;
    }
    return false;
}

bool parseSyntax(std::istream& in, const std::string& fileName, std::vector<SyntaxStatement>& statements,
                 std::string& error)
{
    statements.clear();
    TextLines text(in, fileName);
    if (!text.error().empty())
    {
        error = text.error();
        return false;
    }
    SyntaxParser parser(text, fileName);
    if (parser.parseStatements(statements, 0, 0)) return true;
    statements.clear();
    error = parser.error();
    return false;
}

std::string quoteIfNeeded(const std::string& name) { return needsQuotes(name) ? quoted(name) : name; }

std::string quoted(const std::string& name)
{
    std::string text;
    appendQuoted(text, name);
    return text;
}

void appendQuoted(std::string& out, std::string_view text)
{
    out += '"';
    for (const char c : text)
    {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    out += '"';
}

void writeSyntax(std::ostream& out, const std::vector<SyntaxStatement>& statements, unsigned indent)
{
    SyntaxWriter(out, indent).write(statements);
}

} // namespace osgActor
