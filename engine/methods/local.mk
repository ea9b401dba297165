# engine/methods: Makefile fragment, included from Makefile.am (keeps parallel work in separate files).
