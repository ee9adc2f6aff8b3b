"""The pictures of vibromap's files, one module per picture (the scripts of vibromap-post)."""
