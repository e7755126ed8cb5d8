#!/usr/bin/perl
# ctest docs.code_citations: every citation in the comments of the code points into this repository.
#
# The code cites formulas as  \ref ANCHOR "docs/PAGE.md"  beside the paper they come from (authors, year,
# equation number), e.g.
#     // Montanero and Garzo 2002, eq. (45), \ref son_binary_gamma "docs/sonine.md"
# In a Doxygen comment this renders as a link to the section; in a plain comment the reader opens
# docs/PAGE.md and finds {#ANCHOR}. This script checks, in the comments of src/, tests/, validation/,
# bench/ and examples/ (C++ // and /* */ comments, namelist ! comments, CMake # comments, the Markdown
# pages and the mutants of tests/mutation):
#  1. every \ref NAME names an anchor the docs define ({#NAME} in docs/*.md or a tutorial README, or a
#     \page, \section, \subsection or \anchor of a source file, or a page generated at build time);
#  2. when the link text names a page ("docs/PAGE.md..."), NAME is defined on that page;
#  3. every plain mention docs/PAGE.md (or docs/PAGE.md#NAME) names an existing page (and anchor);
#  4. no comment cites what a clone of the repository does not contain: ERRATA sections, the numbered
#     source documents ("seed 00N"), or paths under shared/ or seeds/.
# Each offender is printed as FILE:LINE: message; the exit status is 1 if there is any.
# String literals are not comments (changing them changes the program's output): citations of the kinds
# of rule 4 inside them are listed as notes and do not fail the test.
#
# usage: perl check_code_citations.pl REPOSITORY_ROOT
use strict;
use warnings;
use File::Find;

my $root = shift @ARGV or die "usage: $0 REPOSITORY_ROOT\n";
chdir $root or die "cannot enter $root: $!\n";

sub slurp {
  my ($f) = @_;
  open(my $h, '<:encoding(UTF-8)', $f) or die "cannot read $f: $!\n";
  local $/;
  my $t = <$h>;
  close $h;
  return $t;
}

# --- anchors -------------------------------------------------------------------------------------
my %anchor_file;    # anchor -> the page (relative path) that defines it
my @pages = grep { -f } (glob('docs/*.md'), glob('examples/README.md'), glob('examples/[0-9][0-9]-*/README.md'));
for my $p (@pages) {
  my $t = slurp($p);
  $t =~ s/^\s*(```|~~~).*?^\s*\1//msg;    # fenced code and `code spans` define no anchor
  $t =~ s/`[^`\n]*`//g;
  while ($t =~ /\{#([A-Za-z0-9_]+)\}/g) { $anchor_file{$1} //= $p; }
}
$anchor_file{$_} //= '(generated)' for qw(input observables_page validation_results mainpage);

my @files;
find({no_chdir => 1, wanted => sub {
  my $f = $File::Find::name;
  return if -d $f;
  return unless $f =~ m{\.(hpp|cpp|h|nml|md|mut)$} || $f =~ m{(^|/)CMakeLists\.txt$};
  push @files, $f;
}}, grep { -d } qw(src tests validation bench examples));
@files = sort @files;
for my $f (grep { /\.(hpp|cpp|h)$/ } @files) {
  my $t = slurp($f);
  while ($t =~ /[\\@](?:page|section|subsection|subsubsection|anchor)\s+([A-Za-z0-9_]+)/g) {
    $anchor_file{$1} //= $f;
  }
}

# --- comments of each kind of file: a list of [line number, text] ---------------------------------
sub cpp_comments {
  my ($t) = @_;
  my (@comments, @strings);
  my $n = length $t;
  my $i = 0;
  my $line = 1;
  my $add = sub {    # text starting at line $l, split into lines
    my ($list, $l, $text) = @_;
    push @$list, [$l++, $_] for split /\n/, $text, -1;
  };
  while ($i < $n) {
    my $c = substr($t, $i, 1);
    my $two = substr($t, $i, 2);
    if ($two eq '//') {
      my $j = index($t, "\n", $i);
      $j = $n if $j < 0;
      $add->(\@comments, $line, substr($t, $i, $j - $i));
      $i = $j;
    } elsif ($two eq '/*') {
      my $j = index($t, '*/', $i + 2);
      $j = $j < 0 ? $n : $j + 2;
      my $text = substr($t, $i, $j - $i);
      $add->(\@comments, $line, $text);
      $line += ($text =~ tr/\n//);
      $i = $j;
    } elsif ($two eq 'R"' && ($i == 0 || substr($t, $i - 1, 1) !~ /\w/)) {
      # raw string: often a namelist, whose ! comments are comments too
      my $k = index($t, '(', $i);
      my $delim = substr($t, $i + 2, $k - $i - 2);
      my $j = index($t, ')' . $delim . '"', $k);
      $j = $j < 0 ? $n : $j + length($delim) + 2;
      my $text = substr($t, $i, $j - $i);
      my $l = $line;
      for my $row (split /\n/, $text, -1) {
        push @comments, [$l, $1] if $row =~ /(!.*)$/;
        $l++;
      }
      $line += ($text =~ tr/\n//);
      $i = $j;
    } elsif ($c eq '"') {
      my $j = $i + 1;
      while ($j < $n && substr($t, $j, 1) ne '"' && substr($t, $j, 1) ne "\n") {
        $j += substr($t, $j, 1) eq '\\' ? 2 : 1;
      }
      push @strings, [$line, substr($t, $i, $j + 1 - $i)];
      $i = $j + 1;
    } elsif ($c eq "'" && !($i > 0 && substr($t, $i - 1, 1) =~ /[0-9A-Fa-f]/)) {   # not a digit separator
      my $j = $i + 1;
      while ($j < $n && substr($t, $j, 1) ne "'" && substr($t, $j, 1) ne "\n") {
        $j += substr($t, $j, 1) eq '\\' ? 2 : 1;
      }
      $i = $j + 1;
    } else {
      $line++ if $c eq "\n";
      $i++;
    }
  }
  return (\@comments, \@strings);
}

sub line_comments {    # text from the first comment character on (outside '...' and "...")
  my ($t, $mark) = @_;
  my @out;
  my $l = 0;
  for my $row (split /\n/, $t, -1) {
    $l++;
    my $q = '';
    for my $k (0 .. length($row) - 1) {
      my $c = substr($row, $k, 1);
      if ($q) { $q = '' if $c eq $q; next; }
      if ($c eq "'" || $c eq '"') { $q = $c; next; }
      if ($c eq $mark) { push @out, [$l, substr($row, $k)]; last; }
    }
  }
  return \@out;
}

sub all_lines {
  my ($t) = @_;
  my $l = 0;
  return [map { [++$l, $_] } split /\n/, $t, -1];
}

# --- the checks ----------------------------------------------------------------------------------
my $forbidden = qr{(ERRATA|§\s*\d|\b[Ss]eeds?\s+0\d\d\b|\bshared/|\bseeds/|(?<![\w/])INTERFACE\.md)};
my ($failures, $refs, $notes) = (0, 0, 0);
sub fail { my ($f, $l, $msg) = @_; print "$f:$l: $msg\n"; $failures++; }

for my $f (@files) {
  my $t = slurp($f);
  my ($comments, $strings);
  if ($f =~ /\.(hpp|cpp|h)$/) { ($comments, $strings) = cpp_comments($t); }
  elsif ($f =~ /\.nml$/) { $comments = line_comments($t, '!'); }
  elsif ($f =~ /CMakeLists\.txt$/) { $comments = line_comments($t, '#'); }
  else { $comments = all_lines($t); }    # Markdown pages, mutants
  for my $n (0 .. $#$comments) {
    my ($l, $text) = @{$comments->[$n]};
    # "seed" at the end of a line and its number at the start of the next comment line
    if ($text =~ /\b[Ss]eeds?\s*$/ && $n < $#$comments && $comments->[$n + 1][0] == $l + 1
        && $comments->[$n + 1][1] =~ m{^\W*0\d\d\b}) {
      fail($f, $l, "cites a seed document across two lines: cite the paper (authors, year, equation)");
    }
    if ($text =~ $forbidden) {
      fail($f, $l, "cites '$1', which is not part of the repository: cite the paper (authors, year, "
        . "equation) and the docs section that states the formula, \\ref ANCHOR \"docs/PAGE.md\"");
    }
    while ($text =~ /[\\@]ref\s+([A-Za-z0-9_][A-Za-z0-9_:.]*[A-Za-z0-9_:])(\s+"([^"]*)")?/g) {
      my ($name, $label) = ($1, $3);
      $refs++;
      if (!exists $anchor_file{$name}) {
        fail($f, $l, "\\ref $name: no such anchor in docs/*.md, the tutorials or a source's \\section");
        next;
      }
      if (defined $label && $label =~ m{^(docs/[\w.-]+\.md)} && $anchor_file{$name} ne $1) {
        fail($f, $l, "\\ref $name \"$label\": $name is defined in $anchor_file{$name}, not in $1");
      }
    }
    while ($text =~ m{(?<![\w/])(docs/[\w.-]+\.md)(?:#([A-Za-z0-9_]+))?}g) {
      my ($page, $name) = ($1, $2);
      if (!-f $page) { fail($f, $l, "$page: no such page"); next; }
      if (defined $name && ($anchor_file{$name} // '') ne $page) {
        fail($f, $l, "$page#$name: no anchor {#$name} on that page");
      }
    }
  }
  for my $s (@{$strings // []}) {
    my ($l, $text) = @$s;
    if ($text =~ $forbidden) {
      print "$f:$l: note: a string literal cites '$1' (program output, not checked)\n";
      $notes++;
    }
  }
}

my $n_files = @files;
my $n_anchors = keys %anchor_file;
if ($failures) {
  print "docs.code_citations: $failures offending citation(s) in the comments of $n_files files\n";
  exit 1;
}
print "docs.code_citations: $refs \\ref citations in $n_files files resolve ($n_anchors anchors); "
  . "no comment cites ERRATA, seed documents or shared/ paths ($notes string literal(s) noted)\n";
exit 0;
