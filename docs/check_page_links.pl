#!/usr/bin/perl
# ctest docs.citations: the cross-references of the Markdown pages hold, read as plain Markdown and as
# the Doxygen site.
#
# The pages (docs/*.md, README.md, the tutorials examples/README.md and examples/NN-name/README.md, the
# READMEs of validation/, paper-figures/, bench/ and tests/) link to a section as a plain Markdown link to
# its heading anchor: [text](page.md#anchor), or [text](#anchor) on the same page, with the heading
# written `## Title {#anchor}`. Any Markdown viewer follows such a link; docs/markdown_math.pl turns it
# into Doxygen's [text](@ref anchor) for the site. This script checks, outside fenced code and code
# spans:
#  1. every link to a local file names a file that exists (relative to the page), and its #anchor is a
#     heading anchor {#anchor} of that file (of the page itself for #anchor alone);
#  2. every [text](@ref NAME) (the pages generated at build time: input, observables_page,
#     validation_results) names a generated page or an anchor;
#  3. no page uses Doxygen's \ref (it reads as markup in a plain viewer), no link text runs over a line
#     break (the filter works line by line), and no line starts with a stray "docs/PAGE.md") left over
#     from a \ref whose text ran over a line;
#  4. a page of the site's own (docs/, examples/) links to no Markdown file outside them (Doxygen cannot
#     resolve it, and the site's build fails on the warning): name such a file as `code` instead.
# Each offender is printed as FILE:LINE: message; the exit status is 1 if there is any.
#
# usage: perl check_page_links.pl REPOSITORY_ROOT
use strict;
use warnings;
use File::Basename qw(dirname);
use File::Spec;

my $root = shift @ARGV or die "usage: $0 REPOSITORY_ROOT\n";
chdir $root or die "cannot enter $root: $!\n";

my @pages = grep { -f } (glob('docs/*.md'), 'README.md', glob('examples/README.md'),
                         glob('examples/[0-9][0-9]-*/README.md'), glob('validation/*/README.md'),
                         glob('paper-figures/README.md'), glob('bench/README.md'), glob('tests/*/README.md'));
my %generated = map { $_ => 1 } qw(input observables_page validation_results mainpage);

sub slurp {
  my ($f) = @_;
  open(my $h, '<', $f) or die "cannot read $f: $!\n";
  local $/;
  return <$h>;
}

# The lines of a page outside fenced code, code spans blanked (their line numbers kept).
sub prose_lines {
  my ($f) = @_;
  my @out;
  my $fence = '';  # the string that opened the fence in force ('' outside one)
  for my $line (split /\n/, slurp($f), -1) {
    if ($line =~ /^\s*(```+|~~~+)/) {
      my $mark = $1;
      if ($fence eq '') { $fence = $mark; push @out, ''; next; }
      if (substr($mark, 0, 1) eq substr($fence, 0, 1) && length($mark) >= length($fence)) { $fence = ''; push @out, ''; next; }
    }
    if ($fence ne '') { push @out, ''; next; }
    (my $prose = $line) =~ s/(`+).*?\1//g;  # code spans of any number of backticks
    push @out, $prose;
  }
  return @out;
}

my %anchors_of;    # normalised page path -> { anchor => 1 }
my %anchor_page;   # anchor -> the page that defines it
sub anchors_of {
  my ($page) = @_;
  return $anchors_of{$page} if $anchors_of{$page};
  my %set;
  for my $line (prose_lines($page)) {
    next unless $line =~ /^#/;
    $set{$1} = 1 while $line =~ /\{#([A-Za-z0-9_]+)\}/g;
  }
  return $anchors_of{$page} = \%set;
}
for my $p (@pages) { $anchor_page{$_} //= $p for keys %{anchors_of($p)}; }

my ($failures, $links) = (0, 0);
sub fail { my ($f, $l, $msg) = @_; print "$f:$l: $msg\n"; $failures++; }

for my $page (@pages) {
  my @lines = prose_lines($page);
  for my $i (0 .. $#lines) {
    my ($l, $text) = ($i + 1, $lines[$i]);
    if ($text =~ /\\ref\s+([A-Za-z0-9_]+)/) {
      my $where = $anchor_page{$1} ? File::Spec->abs2rel($anchor_page{$1}, dirname($page)) : 'PAGE.md';
      fail($page, $l, "\\ref $1: write a Markdown link, [text]($where#$1)");
    }
    if ($text =~ /^([^\[]*?)\]\((?:[^)\s]*\.md)?#[A-Za-z0-9_]+\)/) {
      fail($page, $l, "a link text runs over a line break: keep [text](target) on one line");
    }
    fail($page, $l, "a stray \"...md\") after a link: the rest of a former \\ref's text")
      if $text =~ /^\s*"[\w\/.-]+\.md"\)/;
    while ($text =~ /\]\(([^)\s]+)\)/g) {
      my $target = $1;
      next if $target =~ m{^[a-z][a-z0-9+.-]*:}i;    # https:, mailto:, ...
      $links++;
      if ($target =~ /^\@ref\s*$/ || $target =~ /^\@ref$/) { fail($page, $l, "an empty \@ref"); next; }
      my ($path, $anchor) = $target =~ /^([^#]*)(?:#(.*))?$/;
      if ($path eq '' && !defined $anchor) { fail($page, $l, "an empty link"); next; }
      my $file = $path eq '' ? $page : File::Spec->canonpath(dirname($page) . "/$path");
      $file =~ s{(^|/)(?!\.\.)[^/]+/\.\.(/|$)}{$1}g while $file =~ m{(^|/)(?!\.\.)[^/]+/\.\.(/|$)};
      if (!-e $file) { fail($page, $l, "$target: no such file ($file)"); next; }
      if ($page =~ m{^(docs|examples)/} && $file =~ /\.md$/ && $file !~ m{^(docs|examples)/}) {
        fail($page, $l, "$target: the site (Doxygen) cannot link to a page outside docs/ and examples/: name it as `$file`");
        next;
      }
      next unless defined $anchor;
      if ($file !~ /\.md$/) { fail($page, $l, "$target: an anchor in a file that is not a page"); next; }
      if (!anchors_of($file)->{$anchor}) {
        my $hint = $anchor_page{$anchor} ? " (it is on $anchor_page{$anchor})" : '';
        fail($page, $l, "$target: $file has no heading {#$anchor}$hint");
      }
    }
    while ($text =~ /\]\(\@ref\s+([A-Za-z0-9_]+)\)/g) {
      fail($page, $l, "\@ref $1: no generated page or anchor of that name")
        unless $generated{$1} || $anchor_page{$1};
    }
  }
}

my $n_pages = @pages;
my $n_anchors = keys %anchor_page;
if ($failures) {
  print "$failures broken documentation reference(s)\n";
  exit 1;
}
print "docs.citations: $links links of $n_pages pages resolve ($n_anchors anchors)\n";
