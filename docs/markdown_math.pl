#!/usr/bin/perl
# Doxygen input filter for the Markdown pages (docs/*.md, examples/*/README.md): the pages write
# equations as Markdown math, $...$ inline and $$...$$ displayed (which GitHub and most Markdown
# viewers render), and Doxygen wants \f$...\f$ and \f[...\f]. Fenced code blocks and `code spans`
# are left alone, except that a code span holding a quote (`kind = 'gaussian'`) becomes <code>...</code>:
# Doxygen 1.9 reads a quote before the closing backtick as the end of a `...' quotation. Cross-references
# are plain Markdown links to a page's heading anchor, [text](page.md#anchor) or [text](#anchor) on the
# same page (which any Markdown viewer follows); they become [text](@ref anchor), Doxygen's link to the
# section. Usage (Doxygen FILTER_PATTERNS): perl markdown_math.pl FILE > filtered
use strict;
use warnings;

my $in_fence = 0;
my $in_display = 0;
while (my $line = <>) {
  if ($line =~ /^\s*(```|~~~)/) {
    $in_fence = !$in_fence;
    print $line;
    next;
  }
  if ($in_fence) { print $line; next; }
  if ($line =~ /^\s*\$\$\s*$/) {      # a line holding only $$ opens or closes a displayed equation
    $in_display = !$in_display;
    print $in_display ? "\\f[\n" : "\\f]\n";
    next;
  }
  if ($in_display) { print $line; next; }
  # Outside code spans: links to anchors, then $$...$$ on one line, then $...$.
  my @parts = split /(`[^`]*`)/, $line;
  for my $p (@parts) {
    if ($p =~ /^`(.*)`$/s) {
      my $code = $1;
      if ($code =~ /'/) {
        $code =~ s/&/&amp;/g;
        $code =~ s/</&lt;/g;
        $code =~ s/>/&gt;/g;
        $p = "<code>$code</code>";
      }
      next;
    }
    $p =~ s{\]\((?:[\w./-]*\.md)?#([A-Za-z0-9_]+)\)}{](\@ref $1)}g;
    $p =~ s/\$\$(.+?)\$\$/\\f[$1\\f]/g;
    $p =~ s/(?<![\\\w])\$([^\$\n]+?)\$/\\f\$$1\\f\$/g;
  }
  print join('', @parts);
}
