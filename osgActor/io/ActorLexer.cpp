#include <osgActor/io/ActorLexer>

namespace osgActor {

namespace {

bool endsWord(char c) { return isBlank(c) || c == '{' || c == '}' || c == ';' || c == '#' || c == '"'; }

} // namespace

Token ActorLexer::next()
{
    Token token;
    if (!_inLine)
    {
        if (!_text.nextLine())
        {
            token.type = TokenType::EndOfFile;
            token.line = static_cast<int>(_text.endLineNumber());
            return token;
        }
        _inLine = true;
        _position = 0;
    }
    const std::string_view line = _text.line();
    token.line = static_cast<int>(_text.lineNumber());
    while (_position < line.size() && isBlank(line[_position])) ++_position;
    if (_position == line.size() || line[_position] == '#')
    {
        // The end of the line (after a comment, if any) ends the statement.
        _inLine = false;
        token.type = TokenType::EndOfStatement;
        return token;
    }
    const char c = line[_position++];
    switch (c)
    {
    case ';': token.type = TokenType::EndOfStatement; return token;
    case '{': token.type = TokenType::OpenBrace; return token;
    case '}': token.type = TokenType::CloseBrace; return token;
    case '"':
        token.type = TokenType::String;
        for (;;)
        {
            if (_position == line.size())
            {
                token.type = TokenType::Error;
                token.text = "the string that starts here is not closed on its line";
                return token;
            }
            char s = line[_position++];
            if (s == '"') return token;
            if (s == '\\' && _position < line.size() && (line[_position] == '"' || line[_position] == '\\'))
                s = line[_position++];
            token.text.push_back(s);
        }
    default: break;
    }
    token.type = TokenType::Word;
    const std::size_t start = _position - 1;
    while (_position < line.size() && !endsWord(line[_position])) ++_position;
    token.text.assign(line.data() + start, _position - start);
    return token;
}

} // namespace osgActor
