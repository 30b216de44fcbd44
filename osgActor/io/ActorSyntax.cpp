#include <osgActor/io/ActorLexer>
#include <osgActor/io/ActorSyntax>

#include <ostream>

namespace osgActor {

namespace {

/** Deeper nesting than this is refused rather than risking the stack on a hostile file. */
constexpr unsigned kMaxDepth = 200;

/** One parse of one stream: the lexer, one token of look-ahead and the first error. */
class SyntaxParser
{
public:
    SyntaxParser(TextLines& text, const std::string& fileName) : _lexer(text), _fileName(fileName) { advance(); }

    /** Statements up to the end of the file (depth 0) or to the brace that closes the current block. */
    bool parseStatements(std::vector<SyntaxStatement>& statements, unsigned depth, int openLine)
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

    const std::string& error() const { return _error; }

private:
    bool parseStatement(SyntaxStatement& statement, unsigned depth)
    {
        statement.keyword = _token.text;
        statement.line = _token.line;
        advance();
        while (_token.type == TokenType::Word || _token.type == TokenType::String)
        {
            statement.arguments.push_back(SyntaxArgument{_token.text, _token.type == TokenType::String, _token.line});
            advance();
        }
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
};

bool needsQuotes(const std::string& name)
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

} // namespace

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
    std::string text = "\"";
    for (const char c : name)
    {
        if (c == '"' || c == '\\') text.push_back('\\');
        text.push_back(c);
    }
    text.push_back('"');
    return text;
}

void writeSyntax(std::ostream& out, const std::vector<SyntaxStatement>& statements, unsigned indent)
{
    const std::string margin(indent * 4, ' ');
    for (const SyntaxStatement& statement : statements)
    {
        out << margin << statement.keyword;
        for (const SyntaxArgument& argument : statement.arguments)
            out << ' ' << (argument.quoted ? quoted(argument.text) : argument.text);
        if (statement.hasBlock)
        {
            out << " {\n";
            writeSyntax(out, statement.children, indent + 1);
            out << margin << '}';
        }
        out << '\n';
    }
}

} // namespace osgActor
