#!/bin/sh
# No code (src/, bench/, python/) outside the contact-law registry reads config::ContactLaw (issue
# #26): the enumerators are named only by the registry (src/contact/case_laws.hpp), the descriptions
# (src/contact/*_case.hpp, *_params.hpp: their own) and the enum's declaration (src/contact/law_id.hpp);
# and no law is compared anywhere but in the registry. usage: law_registry_grep.sh SOURCE_DIR
cd "$1" || exit 1
scanned="src bench python"
outside=$(grep -rnE 'ContactLaw::' $scanned --include='*.cpp' --include='*.hpp' |
  grep -vE '^src/contact/case_laws\.hpp:|^src/contact/[a-z_]+_(case|params)\.hpp:|^src/contact/law_id\.hpp:')
compared=$(grep -rnE '(==|!=)[[:space:]]*(config::)?ContactLaw::|ContactLaw::[a-z_]+[[:space:]]*(==|!=)|\.law[[:space:]]*(==|!=)|case[[:space:]]+(config::)?ContactLaw::' \
  $scanned --include='*.cpp' --include='*.hpp' | grep -v '^src/contact/case_laws\.hpp:')
if [ -n "$outside$compared" ]; then
  echo "ContactLaw read outside the registry (ask config::law_of, or add to the law's description):"
  printf '%s\n%s\n' "$outside" "$compared"
  exit 1
fi
# The check must see the registry's own dispatch (else the patterns have gone stale).
grep -qE 'case ContactLaw::hertz_mindlin' src/contact/case_laws.hpp || { echo "the registry's switch was not found"; exit 1; }
echo "no ContactLaw comparison outside src/contact/case_laws.hpp"
