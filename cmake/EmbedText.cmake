# cmake -DIN=file -DOUT=file.cpp -DSYMBOL=name -P EmbedText.cmake
# Writes a C++ source defining `extern const char* const rescuesim::<SYMBOL>` with the file's text.
file(READ ${IN} content HEX)
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${content}")
file(WRITE ${OUT} "// generated from ${IN}\nnamespace rescuesim {\nstatic const char data[] = {${bytes} 0x00};\nextern const char* const ${SYMBOL} = data;\n}\n")
